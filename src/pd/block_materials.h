// Materials by block: a body read from a point file whose blocks (the file's fourth column) carry
// materials of their own ([[flex_body.block_material]]). Each particle takes its block's Young's
// modulus, density and critical stretch; the law (bond-based), the plane and the damping's time
// constant stay the body's. A bond between two materials is as stiff as its two halves in series,
// each in its own material: c_ij = 2 c_i c_j / (c_i + c_j), which is c inside one material. It
// breaks past the smaller of its ends' critical stretches: an interface is as strong as its weaker
// side.
#pragma once

#include <vector>

#include "pd/bond_store.h"
#include "scene/scene_def.h"

namespace periflex {

struct ParticleMaterials {
  std::vector<double> modulus_ratio;     // E_i / E of each particle (E the body's material.youngs_modulus)
  std::vector<double> density;           // rho_i [kg/m^3]
  std::vector<double> critical_stretch;  // s0_i of each particle's material
  bool empty() const { return modulus_ratio.empty(); }
};

// Each of the body's n particles' constants when def.block_materials is not empty (else empty).
// body_s0 is the critical stretch the body's law takes from def.material.
ParticleMaterials particle_materials(const FlexBodyDef& def, int n, double horizon, double body_s0);

// The micromodulus factor of a bond between particles of modulus ratios a and b: its two halves
// in series. The same bits in both directions (a product and a sum of the same two numbers).
inline double series_modulus(double a, double b) { return 2.0 * a * b / (a + b); }

// Writes each particle's critical stretch into bonds.particle_s0 and each row's smallest bond
// threshold into bonds.row_s0 (what the force loops test a row against).
void set_break_stretches(const ParticleMaterials& materials, BondStore& bonds);

}  // namespace periflex
