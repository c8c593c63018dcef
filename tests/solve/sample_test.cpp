// Probe columns of a rigid body: the angular velocity beside the angle, so one probe per body
// gives its whole planar motion.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

TEST(ProbeColumns, RigidProbeReportsTheAngularVelocity) {
  SceneDef s = test::double_pendulum("rk4", 1e-4, CorrectionDef::Method::kProjection);
  s.probes.push_back({"lower_tip", "lower", Vec2(0.5, 0.0), {}});
  Simulation sim(s);
  const auto columns = sim.probe_columns();
  ASSERT_EQ(columns.size(), 6u);
  EXPECT_EQ(columns[4], "probe.lower_tip.angle");
  EXPECT_EQ(columns[5], "probe.lower_tip.omega");
  sim.initialize();
  // omega against the central difference of the angle, at a few instants of chaotic motion
  const double h = 1e-4;
  for (double t : {0.3, 0.71, 1.2}) {
    sim.advance_to(t - h);
    const double before = sim.sample().probe_values[4];
    sim.advance_to(t);
    const double omega = sim.sample().probe_values[5];
    sim.advance_to(t + h);
    const double after = sim.sample().probe_values[4];
    EXPECT_NEAR(omega, (after - before) / (2 * h), 1e-5 * (1 + std::abs(omega))) << "t = " << t;
    EXPECT_GT(std::abs(omega), 0.1);
  }
}

// probe_position, the cheap read, gives the sample's x and y of each probe as the body moves
TEST(ProbeColumns, ProbePositionMatchesTheSample) {
  SceneDef s = test::double_pendulum("rk4", 1e-3, CorrectionDef::Method::kProjection);
  s.probes.push_back({"upper_tip", "upper", Vec2(0.5, 0.0), {}});
  s.probes.push_back({"lower_tip", "lower", Vec2(0.5, 0.0), {}});
  Simulation sim(s);
  sim.initialize();
  for (double t : {0.0, 0.25, 0.8}) {
    sim.advance_to(t);
    const auto values = sim.sample().probe_values;
    for (int p = 0; p < 2; ++p) {
      const Vec2 at = sim.probe_position(p);
      EXPECT_EQ(at.x(), values[6 * p]) << "probe " << p << ", t = " << t;
      EXPECT_EQ(at.y(), values[6 * p + 1]) << "probe " << p << ", t = " << t;
    }
  }
  EXPECT_LT(sim.probe_position(1).y(), -0.5);  // the lower bar has swung down
  EXPECT_THROW(sim.probe_position(2), std::out_of_range);
}

}  // namespace
}  // namespace periflex
