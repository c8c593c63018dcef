// The snapshot filled for drawing (src/solve/snapshot_fill.cpp): ground first, a marker per
// joint where the joint is.
#include <gtest/gtest.h>

#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

TEST(Snapshot, ListsGroundFirstAndMarkersForJoints) {
  Simulation sim(test::double_pendulum("rk4", 1e-3, CorrectionDef::Method::kBaumgarte));
  sim.initialize();
  Snapshot snap;
  sim.fill_snapshot(snap);
  ASSERT_TRUE(snap.geometry);
  ASSERT_EQ(snap.geometry->bodies.size(), 3u);
  EXPECT_TRUE(snap.geometry->bodies[0].ground);
  EXPECT_EQ(snap.bodies.size(), 3u);
  ASSERT_EQ(snap.markers.size(), 2u);
  // the elbow sits at the tip of the upper bar: (1, 0) at rest
  EXPECT_NEAR(snap.markers[1].a.x(), 1.0, 1e-12);
  EXPECT_NEAR(snap.markers[1].a.y(), 0.0, 1e-12);
}

}  // namespace
}  // namespace periflex
