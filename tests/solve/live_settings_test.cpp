// Changes applied between steps: the correction method, the integrator, the step and damping
// (the mouse spring: mouse_spring_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

TEST(LiveSettings, SwitchingToProjectionRemovesAccumulatedDrift) {
  // semi-implicit Euler without correction drifts by ~1e-2 m within 1 s (docs/solver.md)
  Simulation sim(test::double_pendulum("symplectic_euler", 1e-3, CorrectionDef::Method::kNone));
  sim.initialize();
  sim.advance_to(1.0);
  const double drifted = sim.sample().violation_position;
  EXPECT_GT(drifted, 1e-4);
  LiveSettings live = sim.settings();
  live.correction.method = CorrectionDef::Method::kProjection;
  live.correction.tolerance = 1e-10;
  live.correction.max_iterations = 20;
  sim.apply(live);
  sim.step();
  // the first projected step brings the positions back to the tolerance
  EXPECT_LT(sim.sample().violation_position, 1e-10);
  EXPECT_LT(sim.sample().violation_velocity, 1e-8);
}

TEST(LiveSettings, UnknownIntegratorIsRefusedAndTheRunContinues) {
  Simulation sim(test::point_pendulum(1.0, 0.5, "rk4", 1e-3));
  sim.initialize();
  LiveSettings live = sim.settings();
  live.integrator = "no_such_method";
  EXPECT_THROW(sim.apply(live), InputError);
  EXPECT_EQ(sim.settings().integrator, "rk4");
  sim.step();
  EXPECT_EQ(sim.step_count(), 1);
}

TEST(LiveSettings, SameIntegratorWithNewDampingKeepsSteppingOnAParticleScene) {
  Simulation sim(test::small_plate(1e-9));
  sim.initialize();
  const double dt_crit = sim.info().critical_time_step;
  ASSERT_GT(dt_crit, 1e-9);
  LiveSettings live = sim.settings();
  live.global_damping = 10.0;
  live.dt = 0.5 * dt_crit;
  sim.apply(live);  // same integrator: must neither lose it nor refuse the step
  EXPECT_EQ(sim.settings().integrator, "verlet");
  EXPECT_DOUBLE_EQ(sim.settings().global_damping, 10.0);
  sim.step();
  sim.step();
  EXPECT_EQ(sim.step_count(), 2);

  // a step above the bound is refused and the running configuration stays
  live.dt = 100.0 * dt_crit;
  EXPECT_THROW(sim.apply(live), InputError);
  EXPECT_DOUBLE_EQ(sim.settings().dt, 0.5 * dt_crit);
  sim.step();
  EXPECT_EQ(sim.step_count(), 3);
}

}  // namespace
}  // namespace periflex
