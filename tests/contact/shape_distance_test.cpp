// The signed distance of rigid-particle contact against distances worked out by hand.
#include <gtest/gtest.h>

#include <vector>

#include "contact/shape_distance.h"

namespace periflex {
namespace {

TEST(ShapeDistance, RotatedBoxGivesDepthAndOutwardNormalOfTheNearestFace) {
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.center = Vec2(1.0, 2.0);
  box.width = 4.0;
  box.height = 2.0;
  box.angle = kPi / 2;  // the long side now runs along y
  // 0.25 inside the face at x = 1 + 1 (the rotated half-height)
  ShapeDistance d = signed_distance(box, Vec2(1.75, 2.5));
  EXPECT_NEAR(d.distance, -0.25, 1e-12);
  EXPECT_NEAR(d.normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(d.normal.y(), 0.0, 1e-12);
  // outside a corner: distance to the corner (2, 4), normal along the diagonal
  d = signed_distance(box, Vec2(3.0, 5.0));
  EXPECT_NEAR(d.distance, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.normal.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(d.normal.y(), std::sqrt(0.5), 1e-12);
}

TEST(ShapeDistance, CircleBarAndPolygonMatchTheirGeometry) {
  ShapeDef circle;
  circle.kind = ShapeDef::Kind::kCircle;
  circle.radius = 2.0;
  EXPECT_NEAR(signed_distance(circle, Vec2(0.0, -1.5)).distance, -0.5, 1e-12);
  EXPECT_NEAR(signed_distance(circle, Vec2(0.0, -1.5)).normal.y(), -1.0, 1e-12);

  ShapeDef bar;
  bar.kind = ShapeDef::Kind::kBar;
  bar.p1 = Vec2(0.0, 0.0);
  bar.p2 = Vec2(2.0, 0.0);
  bar.radius = 0.1;
  EXPECT_NEAR(signed_distance(bar, Vec2(1.0, 0.05)).distance, -0.05, 1e-12);
  EXPECT_NEAR(signed_distance(bar, Vec2(3.0, 0.0)).distance, 0.9, 1e-12);

  // a counter-clockwise right triangle; inside near the hypotenuse x + y = 1
  ShapeDef triangle;
  triangle.kind = ShapeDef::Kind::kPolygon;
  triangle.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  const ShapeDistance d = signed_distance(triangle, Vec2(0.4, 0.5));
  EXPECT_NEAR(d.distance, -0.1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.normal.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(d.normal.y(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(signed_distance(triangle, Vec2(0.5, -0.2)).distance, 0.2, 1e-12);
  EXPECT_NEAR(signed_distance(triangle, Vec2(0.5, -0.2)).normal.y(), -1.0, 1e-12);
}

TEST(ShapeDistance, ConvexityOfCounterClockwisePolygons) {
  EXPECT_TRUE(is_convex({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}));
  EXPECT_FALSE(is_convex({Vec2(0, 0), Vec2(2, 0), Vec2(1, 0.5), Vec2(2, 1), Vec2(0, 1)}));
}

}  // namespace
}  // namespace periflex
