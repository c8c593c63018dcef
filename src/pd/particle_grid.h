// The particles of a flexible body: a square grid of spacing dx that fills a shape
// (box, circle or polygon) with its holes left out. Each particle sits at the centre of
// its grid cell and keeps integer grid indices, so every reference bond vector is an
// exact integer multiple of dx.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

struct ParticleGrid {
  double spacing = 0.0;             // dx
  Vec2 origin = Vec2::Zero();       // position of grid index (0, 0)
  std::vector<double> x, y;         // reference positions
  std::vector<int32_t> ix, iy;      // grid indices: x = origin.x + ix * dx
  // false: the particles lie off the grid (a point file of any layout, a jittered body): x, y are
  // what counts, ix, iy only the nearest nodes, and bonds keep their own lengths
  bool on_grid = true;
  // each particle's volume [m^3] when a point file gives volumes other than dx^2 thickness (a
  // graded mesh); empty: every particle has dx^2 thickness
  std::vector<double> volume;
  int size() const { return static_cast<int>(x.size()); }
};

// Area of a shape (box, circle, polygon, bar); 0 for none.
double grid_shape_area(const ShapeDef& shape);

// Axis-aligned bounds of a shape.
void grid_shape_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi);

// Particle count the shape would need at spacing dx (area / dx^2, holes ignored): an
// estimate made before anything is allocated.
double estimated_particle_count(const ShapeDef& shape, double dx);

// Fills `shape` minus `holes` with a cell-centred grid of spacing dx. The grid is centred
// on the shape's bounding box, so an axis-aligned box of width n dx holds exactly n columns.
ParticleGrid fill_grid(const ShapeDef& shape, const std::vector<ShapeDef>& holes, double dx);

}  // namespace periflex
