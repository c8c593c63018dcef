#include <algorithm>
#include <cmath>

#include "scene/scene_def.h"
#include "scene/shape_boolean.h"

namespace periflex {

// Distance from p to the segment [a, b].
static double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

bool ShapeDef::contains(const Vec2& p) const {
  switch (kind) {
    case Kind::kNone:
      return false;
    case Kind::kBoolean:
      return boolean_contains(*this, p);
    case Kind::kBox: {
      // Rotate p into the box frame; points on the boundary count as inside.
      const Vec2 local = rotation(-angle) * (p - center);
      return std::abs(local.x()) <= 0.5 * width * (1 + 1e-12) && std::abs(local.y()) <= 0.5 * height * (1 + 1e-12);
    }
    case Kind::kCircle:
      return (p - center).squaredNorm() <= radius * radius * (1 + 1e-12);
    case Kind::kBar:
      return segment_distance(p, p1, p2) <= radius;
    case Kind::kPolygon: {
      // Even-odd ray casting along +x.
      bool inside = false;
      const size_t n = vertices.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2& a = vertices[i];
        const Vec2& b = vertices[j];
        if ((a.y() > p.y()) != (b.y() > p.y())) {
          const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
          if (p.x() < x_cross) inside = !inside;
        }
      }
      return inside;
    }
  }
  return false;
}

}  // namespace periflex
