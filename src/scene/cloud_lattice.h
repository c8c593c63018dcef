// Where the points of a point file or an image sit against the square grid of the body's spacing.
// On it, bonds keep their reference length as a whole grid offset (pd/bond_store.h), as on a
// filled shape; points off it (a mesher's centroids, a jittered set) make a body whose bonds keep
// their own lengths. This finds each point's nearest grid node and refuses, naming the line, what
// cannot be a particle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "scene/particle_cloud.h"

namespace periflex {

struct CloudLattice {
  Vec2 origin = Vec2::Zero();      // grid index (0, 0): the lowest x and the lowest y of the points
  std::vector<int32_t> ix, iy;     // the nearest node: x = origin.x + ix dx (within kLatticeTolerance dx on the grid)
  bool on_grid = true;             // every point within kLatticeTolerance dx of its node
  bool cell_volumes = true;        // every volume within kVolumeTolerance of dx^2 thickness
};

// How far (in spacings) a point may lie from its grid node and still count as on the grid:
// printed coordinates of a few significant digits still land, a point a thousandth of a
// spacing away does not. Off the grid, two points closer than this are coincident.
constexpr double kLatticeTolerance = 1e-6;
// How far (relative) a point's volume may differ from dx^2 thickness and still count as the
// grid cell's (the body then gives every particle exactly that volume).
constexpr double kVolumeTolerance = 1e-6;
// The range of a point's volume against dx^2 thickness: a graded mesh's cells lie well within it,
// a file in the wrong unit (a factor of 1e9 for mm^3 read as m^3) does not.
constexpr double kVolumeRange = 1e3;

// The nearest grid node of every point, and whether all of them lie on the grid. Throws
// InputError naming `file` and the line of two coincident points (on the grid: on one node; off
// it: within kLatticeTolerance dx) or of a volume beyond kVolumeRange times or below 1 /
// kVolumeRange of dx^2 thickness.
CloudLattice place_on_lattice(const ParticleCloud& cloud, double dx, double thickness, const std::string& file);

// As place_on_lattice without the search for coincident points (one pass, no sort): what the
// budget and the device check ask of a cloud the scene reader has already placed.
CloudLattice cloud_nodes(const ParticleCloud& cloud, double dx, double thickness, const std::string& file);

}  // namespace periflex
