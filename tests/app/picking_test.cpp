// What the mouse grabs: a rigid body under the cursor (with its body-fixed grab point), else the
// nearest particle within reach, else nothing. Ground and virtual bodies are never grabbed.
#include "app/picking.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace periflex {
namespace {

// ground, a 2 x 1 box body at (5, 0) turned by 90 degrees, a virtual body at the origin, and
// three particles of spacing 0.1 along the x axis from x = -2
Snapshot make_snapshot() {
  auto g = std::make_shared<SceneGeometry>();
  g->bodies.resize(4);
  g->bodies[0].ground = true;
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.width = 2.0;
  box.height = 1.0;
  g->bodies[1].shapes = {box};
  g->bodies[2].is_virtual = true;
  g->bodies[2].shapes = {box};
  g->bodies[3].shapes = {};
  g->flex_bodies.push_back({"plate", 0, 3, 0.1});
  g->reference_x = {-2.0f, -1.9f, -1.8f};
  g->reference_y = {0.0f, 0.0f, 0.0f};
  Snapshot s;
  s.geometry = g;
  s.bodies.resize(4);
  s.bodies[1] = {5.0, 0.0, kPi / 2};
  s.px = g->reference_x;
  s.py = g->reference_y;
  return s;
}

TEST(Picking, GrabsTheRigidBodyUnderTheCursorAtItsBodyFixedPoint) {
  const Snapshot s = make_snapshot();
  // turned by 90 degrees the box spans y in [-1, 1]: (5, 0.8) is inside, at local (0.8, 0)
  const auto spring = pick(s, Vec2(5.0, 0.8), 0.0);
  ASSERT_TRUE(spring.has_value());
  EXPECT_EQ(spring->body, 0);  // rigid body index: the first body after the ground
  EXPECT_EQ(spring->particle, -1);
  EXPECT_NEAR(spring->local_point.x(), 0.8, 1e-12);  // A(pi/2)^T (0, 0.8): exact up to rounding
  EXPECT_NEAR(spring->local_point.y(), 0.0, 1e-12);
  EXPECT_EQ(spring->target, Vec2(5.0, 0.8));
  // (5.8, 0) lies outside the turned box (it is 0.5 wide along x)
  EXPECT_FALSE(pick(s, Vec2(5.8, 0.0), 0.0).has_value());
}

TEST(Picking, GrabsTheNearestParticleWithinOneSpacing) {
  const Snapshot s = make_snapshot();
  const auto spring = pick(s, Vec2(-1.88, 0.03), 0.0);
  ASSERT_TRUE(spring.has_value());
  EXPECT_EQ(spring->particle, 1);
  EXPECT_EQ(spring->body, -1);
  // farther than one spacing from every particle: nothing, unless the tolerance reaches
  EXPECT_FALSE(pick(s, Vec2(-2.0, 0.3), 0.0).has_value());
  EXPECT_TRUE(pick(s, Vec2(-2.0, 0.3), 0.35).has_value());
}

TEST(Picking, NeverGrabsVirtualBodiesOrTheGround) {
  const Snapshot s = make_snapshot();
  // the virtual body's box covers the origin; no particle is near it
  EXPECT_FALSE(pick(s, Vec2(0.0, 0.0), 0.0).has_value());
  Snapshot empty;
  EXPECT_FALSE(pick(empty, Vec2(0.0, 0.0), 1.0).has_value());
}

// The inspector looks for a particle where it is drawn: with the deformation magnified the
// drawn positions differ from the snapshot's, and the particle drawn under the pointer wins.
TEST(Picking, ParticleAtUsesTheGivenPositions) {
  const Snapshot s = make_snapshot();
  EXPECT_EQ(particle_at(s, s.px, s.py, Vec2(-1.9, 0.02), 0.0), 1);
  // drawn 1 m higher: nothing where they really are, particle 1 where it is drawn
  std::vector<float> drawn_y = {1.0f, 1.0f, 1.0f};
  EXPECT_EQ(particle_at(s, s.px, drawn_y, Vec2(-1.9, 0.02), 0.0), -1);
  EXPECT_EQ(particle_at(s, s.px, drawn_y, Vec2(-1.9, 1.02), 0.0), 1);
  // beyond one spacing of any particle: none
  EXPECT_EQ(particle_at(s, s.px, s.py, Vec2(-1.5, 0.0), 0.0), -1);
}

}  // namespace
}  // namespace periflex
