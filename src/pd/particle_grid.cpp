#include "pd/particle_grid.h"

#include <algorithm>
#include <cmath>

#include "scene/grid_scan.h"
#include "scene/shape_boolean.h"

namespace periflex {

double grid_shape_area(const ShapeDef& shape) {
  switch (shape.kind) {
    case ShapeDef::Kind::kNone:
      return 0.0;
    case ShapeDef::Kind::kBoolean:
      return boolean_area_bound(shape);
    case ShapeDef::Kind::kBox:
      return shape.width * shape.height;
    case ShapeDef::Kind::kCircle:
      return kPi * shape.radius * shape.radius;
    case ShapeDef::Kind::kBar:
      return (shape.p2 - shape.p1).norm() * 2.0 * shape.radius + kPi * shape.radius * shape.radius;
    case ShapeDef::Kind::kPolygon: {
      // shoelace formula; orientation does not matter for the estimate
      double twice = 0.0;
      const size_t n = shape.vertices.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) twice += cross(shape.vertices[j], shape.vertices[i]);
      return 0.5 * std::abs(twice);
    }
  }
  return 0.0;
}

void grid_shape_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi) { shape_bounds(shape, lo, hi); }

double estimated_particle_count(const ShapeDef& shape, double dx) {
  return dx > 0.0 ? grid_shape_area(shape) / (dx * dx) : 0.0;
}

ParticleGrid fill_grid(const ShapeDef& shape, const std::vector<ShapeDef>& holes, double dx) {
  ParticleGrid grid;
  grid.spacing = dx;
  const GridFrame frame = grid_frame(shape, dx);
  grid.origin = frame.origin;

  // the count first, from the same scan, so the arrays are allocated once
  const long n = count_grid_cells(shape, holes, frame);
  grid.x.reserve(n);
  grid.y.reserve(n);
  grid.ix.reserve(n);
  grid.iy.reserve(n);

  // row by row, so particle order follows y then x (neighbours are near in memory); only the
  // shape's own cells are visited
  scan_grid(shape, holes, frame, {}, [&](long j, long begin, long end) {
    for (long i = begin; i < end; ++i) {
      const Vec2 p = frame.cell(i, j);
      grid.x.push_back(p.x());
      grid.y.push_back(p.y());
      grid.ix.push_back(static_cast<int32_t>(i));
      grid.iy.push_back(static_cast<int32_t>(j));
    }
  });
  return grid;
}

}  // namespace periflex
