// Signed distance from a point to the boundary of a shape (box, circle, polygon, bar): the
// penetration measure of rigid-particle contact. Negative inside; the normal is the gradient
// of the distance (the outward unit normal of the nearest boundary point), so a penalty force
// k (margin - distance) normal pushes a particle out along the shortest way.
#pragma once

#include <algorithm>
#include <vector>

#include "core/vec2.h"
#include "scene/scene_def.h"

namespace periflex {

struct ShapeDistance {
  double distance = 0.0;    // > 0 outside, < 0 inside
  Vec2 normal = Vec2::UnitX();  // unit, pointing out of the shape
};

// Distance of `p` (in the frame the shape is given in) to the boundary of `shape`.
ShapeDistance signed_distance(const ShapeDef& shape, const Vec2& p);

// Whether the polygon (vertices counter-clockwise) is convex: no vertex turns clockwise.
bool is_convex(const std::vector<Vec2>& vertices);

// Nearest point of the segment [a, b] to p (a when the segment is a point). Inline: the contact
// passes call it per particle and per edge.
inline Vec2 nearest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

// A circle (centre, radius) enclosing the shape, in the shape's frame: the cheap test before
// the exact distance.
void bounding_circle(const ShapeDef& shape, Vec2& centre, double& radius);

}  // namespace periflex
