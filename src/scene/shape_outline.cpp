#include "scene/shape_outline.h"

#include <algorithm>
#include <cmath>

namespace periflex {

std::vector<Vec2> shape_outline(const ShapeDef& shape, const Vec2& position, double angle, int segments) {
  const Mat2 a = rotation(angle);
  std::vector<Vec2> local;
  switch (shape.kind) {
    case ShapeDef::Kind::kNone:
      break;
    case ShapeDef::Kind::kBoolean:
      // drawn as its first operand (the plate of a plate minus holes)
      if (!shape.operands.empty()) return shape_outline(shape.operands.front(), position, angle, segments);
      break;
    case ShapeDef::Kind::kBox: {
      const Mat2 r = rotation(shape.angle);
      const double hw = 0.5 * shape.width, hh = 0.5 * shape.height;
      for (const Vec2& c : {Vec2(-hw, -hh), Vec2(hw, -hh), Vec2(hw, hh), Vec2(-hw, hh)})
        local.push_back(shape.center + r * c);
      break;
    }
    case ShapeDef::Kind::kCircle:
      for (int i = 0; i < segments; ++i) {
        const double t = 2.0 * kPi * i / segments;
        local.push_back(shape.center + shape.radius * Vec2(std::cos(t), std::sin(t)));
      }
      break;
    case ShapeDef::Kind::kPolygon:
      local = shape.vertices;
      break;
    case ShapeDef::Kind::kBar: {
      // a capsule: half circles around both ends joined by straight sides
      const Vec2 d = shape.p2 - shape.p1;
      const double base = d.norm() > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
      const int half = std::max(4, segments / 2);
      for (int i = 0; i <= half; ++i) {
        const double t = base - 0.5 * kPi + kPi * i / half;
        local.push_back(shape.p2 + shape.radius * Vec2(std::cos(t), std::sin(t)));
      }
      for (int i = 0; i <= half; ++i) {
        const double t = base + 0.5 * kPi + kPi * i / half;
        local.push_back(shape.p1 + shape.radius * Vec2(std::cos(t), std::sin(t)));
      }
      break;
    }
  }
  for (Vec2& p : local) p = position + a * p;
  return local;
}

}  // namespace periflex
