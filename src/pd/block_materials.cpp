#include "pd/block_materials.h"

#include <algorithm>

#include "pd/pd_material.h"

namespace periflex {

ParticleMaterials particle_materials(const FlexBodyDef& def, int n, double horizon, double body_s0) {
  ParticleMaterials out;
  if (def.block_materials.empty()) return out;
  const PdMaterialDef& body = def.material;
  out.modulus_ratio.assign(n, 1.0);
  out.density.assign(n, body.density);
  out.critical_stretch.assign(n, body_s0);
  const std::vector<long>& block = def.particles->block;
  for (const BlockMaterialDef& m : def.block_materials) {
    // the block's own criterion: a stretch as given, or from its fracture energy and modulus
    double s0 = body_s0;
    if (m.critical_stretch > 0.0)
      s0 = m.critical_stretch;
    else if (m.fracture_energy > 0.0)
      s0 = critical_stretch_from_energy(m.fracture_energy, m.youngs_modulus, horizon, body.plane_strain, def.influence);
    for (int i = 0; i < n; ++i) {
      if (block[i] != m.block) continue;
      out.modulus_ratio[i] = m.youngs_modulus / body.youngs_modulus;
      out.density[i] = m.density;
      out.critical_stretch[i] = s0;
    }
  }
  return out;
}

void set_break_stretches(const ParticleMaterials& materials, BondStore& bonds) {
  if (materials.empty()) return;
  const int n = bonds.particle_count();
  bonds.particle_s0 = materials.critical_stretch;
  bonds.row_s0.resize(n);
  for (int i = 0; i < n; ++i) {
    double least = bonds.particle_s0[i];
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) least = std::min(least, bonds.particle_s0[bonds.neighbor[b]]);
    bonds.row_s0[i] = least;
  }
}

}  // namespace periflex
