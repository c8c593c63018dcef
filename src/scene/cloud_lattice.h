// A flexible body's bonds keep their reference length as a whole grid offset (pd/bond_store.h),
// so the particles of a point file or an image must sit on a square grid of the body's spacing.
// This finds each point's grid indices and refuses, naming the line, what cannot be placed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "scene/particle_cloud.h"

namespace periflex {

struct CloudLattice {
  Vec2 origin = Vec2::Zero();      // grid index (0, 0): the lowest x and the lowest y of the points
  std::vector<int32_t> ix, iy;     // x = origin.x + ix dx (to within kLatticeTolerance dx)
};

// How far (in spacings) a point may lie from its grid node: printed coordinates of a few
// significant digits still land, a point half way between nodes does not.
constexpr double kLatticeTolerance = 1e-6;
// How far (relative) a point's volume may differ from dx^2 thickness.
constexpr double kVolumeTolerance = 1e-6;

// The grid indices of every point. Throws InputError naming `file` and the line of the first
// point off the grid, of two points on one node (coincident points) or of a volume other than
// dx^2 thickness (the body gives every particle that volume).
CloudLattice place_on_lattice(const ParticleCloud& cloud, double dx, double thickness, const std::string& file);

}  // namespace periflex
