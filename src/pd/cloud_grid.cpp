#include "pd/cloud_grid.h"

#include "scene/cloud_lattice.h"

namespace periflex {

ParticleGrid grid_from_cloud(const ParticleCloud& cloud, double dx, double thickness) {
  const CloudLattice lattice = place_on_lattice(cloud, dx, thickness, cloud.source);
  ParticleGrid grid;
  grid.spacing = dx;
  grid.origin = lattice.origin;
  // the positions exactly as given: a body written out and read back is the same body
  grid.x = cloud.x;
  grid.y = cloud.y;
  grid.ix = lattice.ix;
  grid.iy = lattice.iy;
  return grid;
}

ParticleGrid body_particles(const FlexBodyDef& def) {
  return def.particles ? grid_from_cloud(*def.particles, def.grid_spacing, def.thickness)
                       : fill_grid(def.shape, def.holes, def.grid_spacing);
}

std::vector<uint8_t> body_no_fail(const FlexBodyDef& def, const ParticleGrid& grid) {
  std::vector<uint8_t> flags(grid.size(), 0);
  for (int i = 0; i < grid.size(); ++i) {
    const Vec2 p(grid.x[i], grid.y[i]);
    for (const ShapeDef& region : def.no_fail_regions) flags[i] |= region.contains(p) ? 1 : 0;
    if (def.particles) flags[i] |= def.particles->no_fail[i];
  }
  return flags;
}

}  // namespace periflex
