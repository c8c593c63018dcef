// The mouse spring (src/solve/mouse_spring.cpp): a grab of a rigid body pulls it with a spring
// whose work is external, settles on the pointer, is no divergence from rest; a grab of a patch of
// particles holds stably and drags it.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

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

TEST(LiveSettings, MouseSpringHoldsAPatchOfParticlesStablyAndDragsIt) {
  SceneDef scene = test::small_plate(1e-9);
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
