// Bond-based peridynamic material constants in 2D (docs/peridynamics.md derives them).
// Volumes carry the thickness t (V = dx^2 t), so the micromodulus c has units N/m^6 and the
// strain energy density of a particle is W = 1/4 sum_j c w(|xi|) s^2 |xi| V_j.
#pragma once

#include <string>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

// Bond micromodulus: plane stress 9E/(pi t delta^3), plane strain 48E/(5 pi t delta^3).
double micromodulus(double youngs_modulus, double thickness, double horizon, bool plane_strain);

// Influence function w(r) normalised so that int_0^delta w(r) r^2 dr = delta^3 / 3 (the bulk
// stiffness of the constant function): constant 1, conical 4 (1 - r/delta).
double influence(FlexBodyDef::Influence kind, double r, double horizon);

// Critical stretch from the fracture energy G0 (energy to break every bond crossing a unit
// crack area): plane stress, constant w: sqrt(4 pi G0 / (9 E delta)); plane strain
// sqrt(5 pi G0 / (12 E delta)); a conical w multiplies either by sqrt(5/4).
double critical_stretch_from_energy(double fracture_energy, double youngs_modulus, double horizon,
                                    bool plane_strain, FlexBodyDef::Influence kind);

// Strain energy density of the continuum under isotropic expansion s = eps: pi c t delta^3 eps^2 / 6
// (= E eps^2 / (1 - nu) with nu = 1/3 in plane stress; 2 (lambda + mu) eps^2 with nu = 1/4 in strain).
double isotropic_energy_density(double c, double thickness, double horizon, double eps);

// Strain energy density of the continuum under uniaxial strain H = diag(eps, 0):
// pi c t delta^3 eps^2 / 16 (= E eps^2 / (2 (1 - nu^2)) with nu = 1/3 in plane stress).
double uniaxial_strain_energy_density(double c, double thickness, double horizon, double eps);

// Strain energy density of the continuum under H = diag(eps, -eps/3), uniaxial stress for the
// implied Poisson ratio (nu = 1/3 plane stress; the same contraction in plane strain, nu = 1/4):
// pi c t delta^3 eps^2 / 18 (= E eps^2 / 2 in plane stress).
double uniaxial_stress_energy_density(double c, double thickness, double horizon, double eps);

// Fraction of the square cell of side 1 centred at (a, b) that lies inside the disc of radius
// m about the origin (grid units): the exact partial volume of a neighbour cut by the horizon.
// (a, b) need not be whole: a neighbour off the grid has its cell centred where it is.
double cell_fraction_in_disc(double a, double b, double m);

// The Poisson ratio bond-based PD implies: 1/3 plane stress, 1/4 plane strain.
double implied_poisson_ratio(bool plane_strain);

}  // namespace periflex
