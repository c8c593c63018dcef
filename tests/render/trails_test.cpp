// Trails (src/render/trails.cpp): one line per moving body centre and per probe, bounded in
// length, started over when the scene changes or time runs backwards.
#include "render/trails.h"

#include <gtest/gtest.h>

#include <memory>

namespace periflex {
namespace {

// The ground and one body, the body at (x, 0) and one probe at (0, y), at time t.
Snapshot frame(const std::shared_ptr<const SceneGeometry>& geometry, double t, double x, double y) {
  Snapshot s;
  s.geometry = geometry;
  s.time = t;
  s.bodies.resize(2);
  s.bodies[1].x = x;
  Snapshot::Probe probe;
  probe.name = "tip";
  probe.position = Vec2(0.0, y);
  s.probes.push_back(probe);
  return s;
}

std::shared_ptr<const SceneGeometry> ground_and_body() {
  auto g = std::make_shared<SceneGeometry>();
  SceneGeometry::Body ground;
  ground.name = "ground";
  ground.ground = true;
  SceneGeometry::Body body;
  body.name = "crank";
  g->bodies = {ground, body};
  return g;
}

TEST(Trails, OneLinePerMovingBodyAndProbeOldestFirstWithoutRepeats) {
  const auto g = ground_and_body();
  Trails trails;
  trails.record(frame(g, 0.0, 1.0, 2.0), 10);
  trails.record(frame(g, 0.1, 1.0, 2.0), 10);  // nothing moved: no point added
  trails.record(frame(g, 0.2, 3.0, 4.0), 10);
  // the ground is left out: the body's line, then the probe's
  ASSERT_EQ(trails.lines().size(), 2u);
  const auto& body = trails.lines()[0];
  const auto& probe = trails.lines()[1];
  ASSERT_EQ(body.size(), 2u);
  EXPECT_EQ(body.front(), Vec2(1.0, 0.0));
  EXPECT_EQ(body.back(), Vec2(3.0, 0.0));
  ASSERT_EQ(probe.size(), 2u);
  EXPECT_EQ(probe.front(), Vec2(0.0, 2.0));
  EXPECT_EQ(probe.back(), Vec2(0.0, 4.0));
}

TEST(Trails, KeepTheLatestPointsUpToTheLimitAndAtLeastTwo) {
  const auto g = ground_and_body();
  Trails trails;
  for (int k = 0; k < 8; ++k) trails.record(frame(g, 0.1 * k, k, -k), 5);
  ASSERT_EQ(trails.lines()[0].size(), 5u);
  EXPECT_EQ(trails.lines()[0].front(), Vec2(3.0, 0.0));
  EXPECT_EQ(trails.lines()[0].back(), Vec2(7.0, 0.0));
  // a limit below two still draws a segment
  Trails short_trails;
  for (int k = 0; k < 4; ++k) short_trails.record(frame(g, 0.1 * k, k, -k), 0);
  EXPECT_EQ(short_trails.lines()[0].size(), 2u);
}

TEST(Trails, StartOverWhenTimeRunsBackwardsOrTheSceneChanges) {
  const auto g = ground_and_body();
  Trails trails;
  trails.record(frame(g, 0.0, 0.0, 0.0), 10);
  trails.record(frame(g, 0.1, 1.0, 1.0), 10);
  // a reset: back to t = 0, the old line goes
  trails.record(frame(g, 0.0, 5.0, 5.0), 10);
  ASSERT_EQ(trails.lines()[0].size(), 1u);
  EXPECT_EQ(trails.lines()[0].front(), Vec2(5.0, 0.0));
  // another scene (a new geometry) at a later time: the old line goes too
  trails.record(frame(g, 0.2, 6.0, 6.0), 10);
  const auto other = ground_and_body();
  trails.record(frame(other, 0.3, 7.0, 7.0), 10);
  ASSERT_EQ(trails.lines()[0].size(), 1u);
  EXPECT_EQ(trails.lines()[0].front(), Vec2(7.0, 0.0));
  // cleared by hand (same scene, time going on): the next point starts a fresh line
  trails.clear();
  EXPECT_TRUE(trails.lines().empty());
  trails.record(frame(other, 0.4, 8.0, 8.0), 10);
  ASSERT_EQ(trails.lines()[0].size(), 1u);
  EXPECT_EQ(trails.lines()[0].front(), Vec2(8.0, 0.0));
}

}  // namespace
}  // namespace periflex
