// Changes applied between steps: the correction method, and the mouse spring.
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

TEST(LiveSettings, MouseSpringPullsABodyAndItsWorkIsExternal) {
  SceneDef scene = test::empty_scene("rk4", 1e-3, CorrectionDef::Method::kBaumgarte);
  scene.gravity = Vec2::Zero();
  scene.bodies.push_back(test::body("puck", 2.0, 0.1, Vec2::Zero()));
  Simulation sim(scene);
  sim.initialize();
  MouseSpring grab;
  grab.body = 0;
  grab.local_point = Vec2(0.1, 0.0);
  grab.target = Vec2(1.0, 0.0);
  sim.set_mouse_spring(grab);
  sim.advance_to(0.1);
  Snapshot snap;
  sim.fill_snapshot(snap);
  EXPECT_GT(snap.bodies[1].x, 0.01);  // pulled towards the target
  const Energies e = sim.sample().energies;
  EXPECT_GT(e.external_work, 0.0);
  // the spring's work is the only energy source: kinetic energy equals it to RK4 accuracy
  EXPECT_NEAR(e.kinetic, e.external_work, 1e-6 * e.external_work);
  sim.set_mouse_spring(std::nullopt);
  const double before = sim.sample().energies.kinetic;
  sim.advance_to(0.2);
  EXPECT_NEAR(sim.sample().energies.kinetic, before, 1e-12 * before);  // released: coasts freely
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

// A small elastic plate, so the explicit stability bound applies to every live change.
SceneDef small_plate(double dt) {
  SceneDef scene = test::empty_scene("verlet", dt, CorrectionDef::Method::kNone);
  scene.gravity = Vec2::Zero();
  FlexBodyDef plate;
  plate.name = "plate";
  plate.shape.kind = ShapeDef::Kind::kBox;
  plate.shape.width = plate.shape.height = 0.01;
  plate.grid_spacing = 1e-3;
  plate.thickness = 1e-3;
  plate.material.youngs_modulus = 1e9;
  plate.material.density = 1000.0;
  plate.material.critical_stretch = 0.01;
  plate.velocity = Vec2(0.1, 0.0);
  scene.flex_bodies.push_back(plate);
  return scene;
}

TEST(LiveSettings, SameIntegratorWithNewDampingKeepsSteppingOnAParticleScene) {
  Simulation sim(small_plate(1e-9));
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
