// The divergence check stops runs whose energy grows far beyond what the model holds and what
// was fed in. A load switched on at t = 0 on a body at rest feeds energy from the first step,
// before every integrator's accounts hold that work (symplectic Euler books a step's work at the
// velocities it started from: none): the first steps must not look like a divergence.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

// A free 2 kg body, no gravity, pushed along x by a constant 3 N force from t = 0.
SceneDef pushed_body(const std::string& integrator) {
  SceneDef s = test::empty_scene(integrator, 1e-3, CorrectionDef::Method::kNone);
  s.gravity = Vec2::Zero();
  s.bodies.push_back(test::body("block", 2.0, 0.1, Vec2::Zero()));
  ForceDef push;
  push.kind = ForceDef::Kind::kForce;
  push.name = "push";
  push.body_i = "block";
  push.direction = Vec2::UnitX();
  push.magnitude = TimeFunction::constant(3.0);
  s.forces.push_back(push);
  return s;
}

class PushedFromRest : public ::testing::TestWithParam<const char*> {};

TEST_P(PushedFromRest, FirstStepsAreNoDivergence) {
  Simulation sim(pushed_body(GetParam()));
  sim.initialize();
  ASSERT_NO_THROW({
    for (int k = 0; k < 10; ++k) sim.step();
  });
  // v = F t / m exactly for a constant force (every one of these integrators is exact for it)
  const Sample row = sim.sample();
  EXPECT_NEAR(sim.time(), 1e-2, 1e-15);
  EXPECT_GT(row.energies.kinetic, 0.0);
  EXPECT_NEAR(row.energies.kinetic, 0.5 * 2.0 * std::pow(3.0 * 1e-2 / 2.0, 2), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Integrators, PushedFromRest,
                         ::testing::Values("symplectic_euler", "verlet", "rk4", "dopri54"));

}  // namespace
}  // namespace periflex
