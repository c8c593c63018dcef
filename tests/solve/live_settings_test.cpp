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

// A 2 kg puck at rest at the origin, no gravity, over a run of `end_time`.
SceneDef puck_scene(const std::string& integrator, double end_time) {
  SceneDef scene = test::empty_scene(integrator, 1e-3, CorrectionDef::Method::kBaumgarte);
  scene.gravity = Vec2::Zero();
  scene.solver.end_time = end_time;
  scene.bodies.push_back(test::body("puck", 2.0, 0.1, Vec2::Zero()));
  return scene;
}

// The puck grabbed 0.1 m right of its centre and pulled towards `target` (stiffness 0: the scene's).
MouseSpring puck_grab(const Vec2& target, double stiffness = 0.0) {
  MouseSpring grab;
  grab.body = 0;
  grab.local_point = Vec2(0.1, 0.0);
  grab.target = target;
  grab.stiffness = stiffness;
  return grab;
}

TEST(LiveSettings, MouseSpringPullsABodyAndItsWorkIsExternal) {
  Simulation sim(puck_scene("rk4", 1.0));
  sim.initialize();
  // given: about 2 Hz for the 2 kg puck, still moving at t = 0.1
  EXPECT_DOUBLE_EQ(sim.set_mouse_spring(puck_grab(Vec2(1.0, 0.0), 315.0)), 315.0);
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

TEST(LiveSettings, MouseSpringOnARigidBodySettlesWithinATwentiethOfTheRun) {
  Simulation sim(puck_scene("rk4", 1.0));
  sim.initialize();
  // mass times (2 pi 20 / end time)^2
  const double omega = 2.0 * 3.14159265358979 * 20.0;
  EXPECT_NEAR(sim.set_mouse_spring(puck_grab(Vec2(1.0, 0.0))), 2.0 * omega * omega, 1e-6 * 2.0 * omega * omega);
  // by a tenth of the run the grab point sits on the target (the centre 0.1 m behind it)
  sim.advance_to(0.1);
  Snapshot snap;
  sim.fill_snapshot(snap);
  EXPECT_NEAR(snap.bodies[1].x, 0.9, 5e-3);
  EXPECT_LT(sim.sample().energies.kinetic, 1e-3 * 0.5 * 31583.0 * 0.9 * 0.9);
}

// A body at rest with no gravity and nothing driving it holds no energy: the first steps of a
// grab feed it all its motion. The spring's stored energy is what it can give, so the divergence
// check must not stop the run (every integrator, the stiffness chosen for the scene).
TEST(LiveSettings, GrabbingARestingBodyIsNotADivergence) {
  for (const std::string integrator : {"symplectic_euler", "verlet", "rk4", "dopri54", "hht"}) {
    SCOPED_TRACE(integrator);
    Simulation sim(puck_scene(integrator, 1.0));
    sim.initialize();
    sim.set_mouse_spring(puck_grab(Vec2(1.0, 0.5)));
    for (int k = 0; k < 20; ++k) ASSERT_NO_THROW(sim.step()) << "step " << k + 1;
    Snapshot snap;
    sim.fill_snapshot(snap);
    EXPECT_GT(snap.bodies[1].x, 1e-3);  // it moves towards the target
  }
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

TEST(LiveSettings, MouseSpringHoldsAPatchOfParticlesStablyAndDragsIt) {
  SceneDef scene = small_plate(1e-9);
  // (the plate keeps its slow drift of 0.1 m/s: the divergence check compares with the energy
  // the model holds, and a plate at rest holds none)
  scene.flex_bodies[0].material.critical_stretch = 10.0;  // no breaking: the drag only deforms
  Simulation sim(scene);
  sim.initialize();
  LiveSettings live = sim.settings();
  live.dt = 0.6 * sim.info().critical_time_step;
  sim.apply(live);
  Snapshot snap;
  sim.fill_snapshot(snap);
  // the particle nearest the plate's centre
  int grabbed = 0;
  for (int i = 0; i < static_cast<int>(snap.px.size()); ++i) {
    if (std::hypot(snap.px[i], snap.py[i]) < std::hypot(snap.px[grabbed], snap.py[grabbed])) grabbed = i;
  }
  const Vec2 start(snap.px[grabbed], snap.py[grabbed]);
  MouseSpring grab;
  grab.particle = grabbed;
  grab.target = start;
  const double stiffness = sim.set_mouse_spring(grab);
  // the patch within one horizon holds several particles: stiffer than one particle's share
  // at the same frequency (0.3 / dt for this step, 0.6 of the critical one)
  const double omega = 0.3 / live.dt;
  const double particle_mass = 1000.0 * 1e-3 * 1e-3 * 1e-3;
  EXPECT_GT(stiffness, 5.0 * particle_mass * omega * omega);
  EXPECT_LT(stiffness, 50.0 * particle_mass * omega * omega);
  // a drag of 2 mm: the same grab again moves the target only (same stiffness)
  grab.target = start + Vec2(2e-3, 0.0);
  EXPECT_DOUBLE_EQ(sim.set_mouse_spring(grab), stiffness);
  // the anchor walks the 2 mm at its capped speed (solve/mouse_grip.h), then the patch settles
  sim.fill_snapshot(snap);
  ASSERT_GT(snap.mouse.max_speed, 0.0);
  const long steps = static_cast<long>(2e-3 / snap.mouse.max_speed / live.dt) + 3000;
  for (long k = 0; k < steps; ++k) sim.step();  // a NumericalError here fails the test
  sim.fill_snapshot(snap);
  const Vec2 now(snap.px[grabbed], snap.py[grabbed]);
  EXPECT_TRUE(std::isfinite(now.x()) && std::isfinite(now.y()));
  // the patch follows: the grabbed particle has moved most of the way (the plate holds it back)
  EXPECT_GT(now.x() - start.x(), 1e-3);
  EXPECT_LT(std::abs(now.y() - start.y()), 2e-4);
  EXPECT_LT(now.x() - start.x(), 2e-3 + steps * live.dt * 0.1 + 1e-4);
  EXPECT_EQ(sim.set_mouse_spring(std::nullopt), 0.0);
}

}  // namespace
}  // namespace periflex
