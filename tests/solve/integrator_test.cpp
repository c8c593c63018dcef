// Each integrator against a closed form: a mass on a linear spring to the ground (no gravity),
// x(t) = A cos(w t). The error ratio on halving dt shows the order of each method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

constexpr double kMass = 2.0, kStiffness = 50.0, kAmplitude = 0.1;

SceneDef oscillator(const std::string& integrator, double dt) {
  SceneDef s = test::empty_scene(integrator, dt, CorrectionDef::Method::kBaumgarte);
  s.gravity = Vec2::Zero();
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-12;
  s.bodies.push_back(test::body("mass", kMass, 1.0, Vec2(1.0 + kAmplitude, 0.0)));
  ForceDef spring;
  spring.kind = ForceDef::Kind::kSpringDamper;
  spring.name = "spring";
  spring.body_i = "ground";
  spring.body_j = "mass";
  spring.point_i = Vec2::Zero();
  spring.stiffness = kStiffness;
  spring.free_length = 1.0;
  s.forces.push_back(spring);
  return s;
}

double error_at_end(const std::string& integrator, double dt) {
  Simulation sim(oscillator(integrator, dt));
  sim.initialize();
  const double end = 1.0;
  sim.advance_to(end);
  Snapshot snap;
  sim.fill_snapshot(snap);
  const double exact = 1.0 + kAmplitude * std::cos(std::sqrt(kStiffness / kMass) * end);
  return std::abs(snap.bodies[1].x - exact);
}

// observed order log2(e(dt) / e(dt/2)) within 0.3 of the nominal one (asymptotic regime)
void expect_order(const std::string& integrator, double dt, double order) {
  const double e1 = error_at_end(integrator, dt), e2 = error_at_end(integrator, dt / 2);
  const double observed = std::log2(e1 / e2);
  EXPECT_NEAR(observed, order, 0.3) << integrator << " errors " << e1 << " " << e2;
  std::printf("%s: error %.3e at dt=%g, observed order %.2f\n", integrator.c_str(), e1, dt, observed);
}

TEST(Integrators, SymplecticEulerIsFirstOrder) { expect_order("symplectic_euler", 1e-3, 1.0); }
TEST(Integrators, VerletIsSecondOrder) { expect_order("verlet", 1e-3, 2.0); }
TEST(Integrators, Rk4IsFourthOrder) { expect_order("rk4", 2e-2, 4.0); }

TEST(Integrators, DormandPrinceMeetsItsTolerance) {
  // rtol 1e-10 on an O(0.1) amplitude: the global error after ~1 period stays below 1e-8
  EXPECT_LT(error_at_end("dopri54", 0.1), 1e-8);
}

TEST(Integrators, UnknownNameIsRejected) {
  EXPECT_THROW(Simulation(oscillator("leapfrog_9000", 1e-3)), InputError);
  const auto names = integrator_names();
  for (const char* name : {"symplectic_euler", "verlet", "rk4", "dopri54"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
}

TEST(Integrators, AdvanceToLandsExactlyOnTheRequestedTime) {
  Simulation sim(oscillator("rk4", 0.03));
  sim.initialize();
  sim.advance_to(0.1);  // 3 steps of 0.03 and one of 0.01
  EXPECT_EQ(sim.time(), 0.1);
  EXPECT_EQ(sim.step_count(), 4);
  sim.advance_to(0.1);  // nothing to do
  EXPECT_EQ(sim.step_count(), 4);
}

TEST(Integrators, SwitchingIntegratorBetweenStepsKeepsTheSolution) {
  Simulation sim(oscillator("rk4", 1e-3));
  sim.initialize();
  sim.advance_to(0.5);
  LiveSettings live = sim.settings();
  live.integrator = "dopri54";
  live.dt = 1e-2;
  sim.apply(live);
  EXPECT_EQ(sim.settings().integrator, "dopri54");
  sim.advance_to(1.0);
  Snapshot snap;
  sim.fill_snapshot(snap);
  const double exact = 1.0 + kAmplitude * std::cos(std::sqrt(kStiffness / kMass) * 1.0);
  EXPECT_NEAR(snap.bodies[1].x, exact, 1e-8);  // both parts accurate to ~1e-10
  EXPECT_EQ(sim.time(), 1.0);
}

TEST(Integrators, EnergyBalanceAccountsForDampingAndActuation) {
  // damper and actuator on the oscillator: kinetic + elastic + dissipated - external stays
  // at its initial value to the RK4 error (~1e-9 J on ~0.25 J)
  SceneDef scene = oscillator("rk4", 1e-3);
  scene.forces[0].damping = 1.5;
  scene.forces[0].actuator = TimeFunction::linear(0.5, 2.0);
  Simulation sim(scene);
  sim.initialize();
  sim.advance_to(2.0);
  const Energies e = sim.sample().energies;
  EXPECT_GT(e.dissipated, 1e-2);
  EXPECT_GT(std::abs(e.external_work), 1e-3);
  EXPECT_LT(std::abs(e.balance), 1e-7);
}

}  // namespace
}  // namespace periflex
