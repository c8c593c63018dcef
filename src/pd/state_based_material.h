// Constants of the 2D ordinary state-based model (linear peridynamic solid, LPS) in the form
// docs/peridynamics.md derives: per particle the energy density
//   W = kappa/2 theta^2 + (4 mu / m) sum_j w (e_j - theta |xi_j| / 2)^2 V_j,
// theta = (2 / m) sum_j w |xi_j| e_j V_j the area dilatation, m = sum_j w |xi_j|^2 V_j the
// weighted volume, e = |y| - |xi| the extension. kappa is the 2D bulk modulus, which alone tells
// plane stress from plane strain.
#pragma once

#include "scene/scene_def.h"

namespace periflex {

// Shear modulus mu = E / (2 (1 + nu)), the same in plane stress and plane strain.
double lps_shear_modulus(double youngs_modulus, double poisson_ratio);

// 2D bulk modulus (stress / area dilatation): plane stress E / (2 (1 - nu)), plane strain
// E / (2 (1 + nu) (1 - 2 nu)).
double lps_bulk_modulus(double youngs_modulus, double poisson_ratio, bool plane_strain);

// Critical stretch from the fracture energy G0, Madenci & Oterkus, Peridynamic Theory and Its
// Applications (2014), ch. 6, 2D ordinary state-based: s0 = sqrt(G0 / ((6 mu / pi + 16 (kappa - 2 mu)
// / (9 pi^2)) delta)) for a constant influence function; a conical one multiplies it by sqrt(6/5)
// (the ratio of int w r^4 dr / int w r^3 dr, which sets the energy of the bonds crossing a crack
// line). At nu = 1/3 (plane stress) or 1/4 (plane strain) kappa = 2 mu and it equals the bond-based s0.
double lps_critical_stretch_from_energy(double fracture_energy, double youngs_modulus, double poisson_ratio,
                                        double horizon, bool plane_strain, FlexBodyDef::Influence kind);

}  // namespace periflex
