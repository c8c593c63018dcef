// The contact manifold of two convex rounded shapes: the points through which two rigid outlines
// touch, however deep they lie in each other. Each shape is a convex core (a polygon's corners
// counter-clockwise, or a bar's two end centres) widened by a radius (0 for a box or polygon, the
// half-width for a bar); both given in one frame.
//
// How the points are found (the clipped manifold of rigid-body engines, worked out here for a
// penalty law):
//  - The separating axis test over the edge normals of both cores (and, for a bar, its length
//    axis) gives the face of least penetration: the reference face, its outward normal n.
//  - The other shape's edge facing it most squarely (the incident edge) is clipped to the
//    reference face's extent; each of its clipped end points that lies less than the two radii
//    above the face is a contact, with depth = radius_a + radius_b - its height above the face.
//  - Cores that do not overlap but come within the two radii of each other near a corner (a
//    bar's round end at a box's corner) touch at one point, along the line of their nearest
//    points.
// Every point of the incident edge lies at least as high as the deepest corner, so no point is
// deeper than the least penetration. For a fixed face and incident corner the force k d n at the
// corner is the exact gradient of k d^2 / 2: the penalty law stays conservative while the same
// features touch, so two shapes crossed deep in each other give back the energy stored in them.
#pragma once

#include <array>
#include <vector>

#include "core/vec2.h"

namespace periflex {

struct ManifoldPoint {
  Vec2 point = Vec2::Zero();  // midway between the two surfaces along the normal
  double depth = 0.0;         // > 0
};

struct ContactManifold {
  Vec2 normal = Vec2::UnitX();  // unit, out of b towards a: pushing a along it separates them
  int count = 0;                // 0, 1 or 2 points
  std::array<ManifoldPoint, 2> points{};
};

// The manifold of shape a (core `a`, radius `radius_a`) against shape b; false (count 0) when
// they do not touch. Cores of at least two points; a polygon's counter-clockwise and convex.
bool convex_manifold(const std::vector<Vec2>& a, double radius_a, const std::vector<Vec2>& b, double radius_b,
                     ContactManifold& out);

}  // namespace periflex
