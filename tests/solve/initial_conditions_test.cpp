// The start of a run (src/solve/initial_conditions.cpp): initial positions and velocities that
// break the constraints are projected onto them and the corrections reported.
#include <gtest/gtest.h>

#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

TEST(InitialConditions, InconsistentPositionsAndVelocitiesAreProjectedAndReported) {
  // the bob starts 1 cm too far out along the rod, moving partly along the rod
  SceneDef scene = test::point_pendulum(1.0, kPi / 2, "rk4", 1e-3);
  scene.bodies[0].position.x() += 0.01;
  scene.bodies[0].velocity = Vec2(0.3, -1.0);
  Simulation sim(scene);
  sim.initialize();
  const Sample s = sim.sample();
  EXPECT_LT(s.violation_position, 1e-10);
  EXPECT_LT(s.violation_velocity, 1e-10);
  // the mass-weighted least change moves the bob back by the 1 cm (phi is nearly free: zero inertia)
  EXPECT_NEAR(sim.info().initial_position_correction, 0.01, 1e-6);
  // the radial 0.3 m/s is removed, the tangential -1 m/s is kept
  EXPECT_GE(sim.info().initial_velocity_correction, 0.3 - 1e-9);
  // m v^2 = 1 * 1^2; the zero-inertia angle carries a weight of 1e-6 of the reference mass in
  // the projection, so the kept speed is exact to that relative order
  EXPECT_NEAR(2.0 * s.energies.kinetic, 1.0, 1e-5);
}

}  // namespace
}  // namespace periflex
