// Signed distance from a point to the boundary of a shape (box, circle, polygon, bar): the
// penetration measure of rigid-particle contact. Negative inside; the normal is the gradient
// of the distance (the outward unit normal of the nearest boundary point), so a penalty force
// k (margin - distance) normal pushes a particle out along the shortest way.
#pragma once

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

// Overlap of two convex polygons (vertices counter-clockwise, one frame) by the separating axis
// test over the edge normals of both: the smallest penetration, the axis along which pushing
// `a` out of `b` by it separates them (unit, from b towards a), and a point of the overlap (the
// mean of the points where the edges of the two cross; the middle of the overlap when no corner
// of either lies inside the other). False when some axis separates them.
struct PolygonOverlap {
  double depth = 0.0;
  Vec2 normal = Vec2::UnitX();
  Vec2 point = Vec2::Zero();
};
bool polygon_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, PolygonOverlap& out);

// Whether the polygon (vertices counter-clockwise) is convex: no vertex turns clockwise.
bool is_convex(const std::vector<Vec2>& vertices);

// A circle (centre, radius) enclosing the shape, in the shape's frame: the cheap test before
// the exact distance.
void bounding_circle(const ShapeDef& shape, Vec2& centre, double& radius);

}  // namespace periflex
