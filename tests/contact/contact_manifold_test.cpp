// The clipped contact manifold of two convex rounded shapes against points, depths and normals
// worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "contact/contact_manifold.h"

namespace periflex {
namespace {

// Counter-clockwise corners of a w x h rectangle centred at (cx, cy).
std::vector<Vec2> rect(double cx, double cy, double w, double h) {
  return {Vec2(cx - w / 2, cy - h / 2), Vec2(cx + w / 2, cy - h / 2), Vec2(cx + w / 2, cy + h / 2),
          Vec2(cx - w / 2, cy + h / 2)};
}

TEST(ContactManifold, RectanglesCrossedLikeAPlusSignTouchAtBothCornersOfTheIncidentFace) {
  // a 1 x 3 rectangle raised by 0.25 across a 4 x 1 one: no corner inside the other. Pushing
  // the tall one up by 0.5 + 1.25 = 1.75 frees it (down: 2.25, sideways: 2.5); its bottom face,
  // clipped to the long one's top face, gives its two corners, each 1.75 deep
  ContactManifold m;
  ASSERT_TRUE(convex_manifold(rect(0.0, 0.25, 1.0, 3.0), 0.0, rect(0.0, 0.0, 4.0, 1.0), 0.0, m));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.x(), 0.0, 1e-12);
  EXPECT_NEAR(m.normal.y(), 1.0, 1e-12);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.points[k].depth, 1.75, 1e-12);
    // midway between the corner (y = -1.25) and the face (y = 0.5)
    EXPECT_NEAR(m.points[k].point.y(), -0.375, 1e-12);
    EXPECT_NEAR(std::abs(m.points[k].point.x()), 0.5, 1e-12);
  }
  // the other way round the normal turns
  ASSERT_TRUE(convex_manifold(rect(0.0, 0.0, 4.0, 1.0), 0.0, rect(0.0, 0.25, 1.0, 3.0), 0.0, m));
  EXPECT_NEAR(m.normal.y(), -1.0, 1e-12);
  // apart, and touching only along a line: nothing
  EXPECT_FALSE(convex_manifold(rect(3.0, 0.0, 1.0, 3.0), 0.0, rect(0.0, 0.0, 4.0, 1.0), 0.0, m));
  EXPECT_FALSE(convex_manifold(rect(2.5, 0.0, 1.0, 3.0), 0.0, rect(0.0, 0.0, 4.0, 1.0), 0.0, m));
}

TEST(ContactManifold, BoxOverhangingAFaceIsClippedToTheFacesEnd) {
  // a 2 x 1 box sunk 0.1 into the top of a 4 x 1 box, overhanging its right end by 0.5: one
  // contact at its corner inside (x = 1), one where its face leaves the face below (x = 2)
  ContactManifold m;
  ASSERT_TRUE(convex_manifold(rect(2.0, 0.9, 2.0, 1.0), 0.0, rect(0.0, 0.0, 4.0, 1.0), 0.0, m));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.y(), 1.0, 1e-12);
  const double x0 = std::min(m.points[0].point.x(), m.points[1].point.x());
  const double x1 = std::max(m.points[0].point.x(), m.points[1].point.x());
  EXPECT_NEAR(x0, 1.0, 1e-12);
  EXPECT_NEAR(x1, 2.0, 1e-12);
  EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
  EXPECT_NEAR(m.points[1].depth, 0.1, 1e-12);
}

TEST(ContactManifold, BarsCrossedDeepAtFortyFiveDegreesArePushedThroughTheDeepestEnd) {
  // a bar along x (core from -1 to 1, radius 0.1) and one at 45 degrees through (0, 0.05) (core
  // half-length 0.4, radius 0.1): the ends of neither lie within reach of the other's core. The
  // least penetration is along +y: the lower end centre of the tilted bar, at
  // y = 0.05 - 0.4 sin 45 = -0.2328, lies 0.4328 under where the two radii would just touch
  const double c = 0.4 * std::sqrt(0.5);
  const std::vector<Vec2> flat = {Vec2(-1.0, 0.0), Vec2(1.0, 0.0)};
  const std::vector<Vec2> tilted = {Vec2(-c, 0.05 - c), Vec2(c, 0.05 + c)};
  ContactManifold m;
  ASSERT_TRUE(convex_manifold(tilted, 0.1, flat, 0.1, m));
  ASSERT_EQ(m.count, 1);  // the upper end lies far above the face
  EXPECT_NEAR(m.normal.x(), 0.0, 1e-12);
  EXPECT_NEAR(m.normal.y(), 1.0, 1e-12);
  EXPECT_NEAR(m.points[0].depth, 0.2 + (c - 0.05), 1e-12);
  // at the lower end's x, midway between the two surfaces
  EXPECT_NEAR(m.points[0].point.x(), -c, 1e-12);
  EXPECT_NEAR(m.points[0].point.y(), (0.05 - c - 0.1) + 0.5 * m.points[0].depth, 1e-12);
}

TEST(ContactManifold, RoundBarEndAtABoxCornerTouchesOnlyWithinItsRadius) {
  // a bar along the diagonal beyond the corner (1, 1) of the unit square, radius 0.2
  const std::vector<Vec2> square = rect(0.5, 0.5, 1.0, 1.0);
  ContactManifold m;
  // end centre at (1.1, 1.1): 0.1414 from the corner, within the radius: one contact along the
  // diagonal, 0.2 - 0.1414 deep
  ASSERT_TRUE(convex_manifold({Vec2(1.1, 1.1), Vec2(2.0, 2.0)}, 0.2, square, 0.0, m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.normal.y(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.points[0].depth, 0.2 - 0.1 * std::sqrt(2.0), 1e-12);
  // end centre at (1.15, 1.15): 0.212 from the corner, out of reach, though only 0.15 beyond
  // either face's line
  EXPECT_FALSE(convex_manifold({Vec2(1.15, 1.15), Vec2(2.0, 2.0)}, 0.2, square, 0.0, m));
  // two bars end to end in one line, 0.3 apart between end centres (radii 0.2): they touch
  ASSERT_TRUE(convex_manifold({Vec2(1.3, 0.0), Vec2(2.0, 0.0)}, 0.2, {Vec2(0.0, 0.0), Vec2(1.0, 0.0)}, 0.2, m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(m.points[0].depth, 0.1, 1e-12);
  // and 0.5 apart they do not
  EXPECT_FALSE(convex_manifold({Vec2(1.5, 0.0), Vec2(2.0, 0.0)}, 0.2, {Vec2(0.0, 0.0), Vec2(1.0, 0.0)}, 0.2, m));
}

}  // namespace
}  // namespace periflex
