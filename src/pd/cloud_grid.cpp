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
  grid.on_grid = lattice.on_grid;
  if (!lattice.cell_volumes) grid.volume = cloud.volume;
  return grid;
}

namespace {

// A number in [0, 1) from (seed, index) alone (SplitMix64's finaliser): the same moves on any
// machine and thread count, independent of the particle order anywhere else.
double unit_random(uint64_t seed, uint64_t index) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + index + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1p-53;
}

}  // namespace

void jitter_particles(ParticleGrid& grid, double jitter, uint64_t seed) {
  if (!(jitter > 0.0)) return;
  const double reach = jitter * grid.spacing;
  for (int i = 0; i < grid.size(); ++i) {
    grid.x[i] += reach * (2.0 * unit_random(seed, 2 * static_cast<uint64_t>(i)) - 1.0);
    grid.y[i] += reach * (2.0 * unit_random(seed, 2 * static_cast<uint64_t>(i) + 1) - 1.0);
  }
  grid.on_grid = false;
}

ParticleGrid body_particles(const FlexBodyDef& def) {
  ParticleGrid grid = def.particles ? grid_from_cloud(*def.particles, def.grid_spacing, def.thickness)
                                    : fill_grid(def.shape, def.holes, def.grid_spacing);
  jitter_particles(grid, def.jitter, def.jitter_seed);
  return grid;
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
