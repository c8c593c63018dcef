// Shapes for the scene tests, built in code: a box, a circle, a combination of shapes.
#pragma once

#include <utility>
#include <vector>

#include "scene/scene_def.h"

namespace periflex::test {

inline ShapeDef box(Vec2 c, double w, double h, double angle = 0.0) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBox;
  s.center = c;
  s.width = w;
  s.height = h;
  s.angle = angle;
  return s;
}

inline ShapeDef circle(Vec2 c, double r) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kCircle;
  s.center = c;
  s.radius = r;
  return s;
}

// `how` of the operands (union, difference: the first minus the others, intersection).
inline ShapeDef combined(ShapeDef::Combine how, std::vector<ShapeDef> operands) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBoolean;
  s.combine = how;
  s.operands = std::move(operands);
  return s;
}

}  // namespace periflex::test
