#include "pd/particle_grid.h"

#include <algorithm>
#include <cmath>

namespace periflex {

double grid_shape_area(const ShapeDef& shape) {
  switch (shape.kind) {
    case ShapeDef::Kind::kNone:
      return 0.0;
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

void grid_shape_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi) {
  lo = Vec2::Zero();
  hi = Vec2::Zero();
  switch (shape.kind) {
    case ShapeDef::Kind::kNone:
      return;
    case ShapeDef::Kind::kBox: {
      // the rotated half-extents projected on the axes
      const double c = std::abs(std::cos(shape.angle)), s = std::abs(std::sin(shape.angle));
      const Vec2 half(0.5 * (shape.width * c + shape.height * s), 0.5 * (shape.width * s + shape.height * c));
      lo = shape.center - half;
      hi = shape.center + half;
      return;
    }
    case ShapeDef::Kind::kCircle:
      lo = shape.center - Vec2(shape.radius, shape.radius);
      hi = shape.center + Vec2(shape.radius, shape.radius);
      return;
    case ShapeDef::Kind::kBar:
      lo = shape.p1.cwiseMin(shape.p2) - Vec2(shape.radius, shape.radius);
      hi = shape.p1.cwiseMax(shape.p2) + Vec2(shape.radius, shape.radius);
      return;
    case ShapeDef::Kind::kPolygon:
      if (shape.vertices.empty()) return;
      lo = hi = shape.vertices.front();
      for (const Vec2& v : shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      return;
  }
}

double estimated_particle_count(const ShapeDef& shape, double dx) {
  return dx > 0.0 ? grid_shape_area(shape) / (dx * dx) : 0.0;
}

ParticleGrid fill_grid(const ShapeDef& shape, const std::vector<ShapeDef>& holes, double dx) {
  ParticleGrid grid;
  grid.spacing = dx;
  Vec2 lo, hi;
  grid_shape_bounds(shape, lo, hi);
  const Vec2 mid = 0.5 * (lo + hi);

  // cells per axis: the extent in cells, plus one spare column each side that the
  // inside test removes again (keeps the parity, so aligned boxes are filled exactly)
  const long nx = std::lround((hi.x() - lo.x()) / dx) + 2;
  const long ny = std::lround((hi.y() - lo.y()) / dx) + 2;
  grid.origin = mid - 0.5 * dx * Vec2(static_cast<double>(nx - 1), static_cast<double>(ny - 1));

  // row by row, so particle order follows y then x (neighbours are near in memory)
  for (long j = 0; j < ny; ++j) {
    for (long i = 0; i < nx; ++i) {
      const Vec2 p = grid.origin + dx * Vec2(static_cast<double>(i), static_cast<double>(j));
      if (!shape.contains(p)) continue;
      bool in_hole = false;
      for (const ShapeDef& h : holes) in_hole = in_hole || h.contains(p);
      if (in_hole) continue;
      grid.x.push_back(p.x());
      grid.y.push_back(p.y());
      grid.ix.push_back(static_cast<int32_t>(i));
      grid.iy.push_back(static_cast<int32_t>(j));
    }
  }
  return grid;
}

}  // namespace periflex
