// Probe columns of a rigid body: the angular velocity beside the angle, so one probe per body
// gives its whole planar motion.
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace periflex
