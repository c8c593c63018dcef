// A conservative double pendulum: the energy balance stays near zero with each correction
// method, and the constraint drift grows without correction but stays bounded with
// Baumgarte stabilisation or coordinate projection.
#include <gtest/gtest.h>

#include <cmath>

#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

struct RunResult {
  double worst_balance = 0.0;
  double drift_early = 0.0, drift_late = 0.0, worst_drift = 0.0;
};

RunResult run(const std::string& integrator, double dt, CorrectionDef::Method method, double end) {
  Simulation sim(test::double_pendulum(integrator, dt, method));
  sim.initialize();
  RunResult r;
  for (int k = 1; k <= 200; ++k) {
    sim.advance_to(end * k / 200.0);
    const Sample s = sim.sample();
    r.worst_balance = std::max(r.worst_balance, std::abs(s.energies.balance));
    r.worst_drift = std::max(r.worst_drift, s.violation_position);
    if (k == 20) r.drift_early = s.violation_position;
    if (k == 200) r.drift_late = s.violation_position;
  }
  return r;
}

// Energy scale: m g L of one bar is 9.81 J; the balance bounds are fractions of that.
TEST(EnergyBalance, DoublePendulumConservesEnergyWithEachCorrection) {
  const double end = 10.0;
  // RK4 at dt = 1e-3 over 10 s of chaotic motion: integration error ~1e-7 J; 1e-5 J bound
  const RunResult none = run("rk4", 1e-3, CorrectionDef::Method::kNone, end);
  const RunResult baumgarte = run("rk4", 1e-3, CorrectionDef::Method::kBaumgarte, end);
  const RunResult projection = run("rk4", 1e-3, CorrectionDef::Method::kProjection, end);
  EXPECT_LT(none.worst_balance, 1e-5);
  EXPECT_LT(baumgarte.worst_balance, 1e-5);
  EXPECT_LT(projection.worst_balance, 1e-5);
  std::printf("double pendulum 10 s rk4 dt=1e-3 max |balance| [J]: none %.3e, baumgarte %.3e, projection %.3e\n",
              none.worst_balance, baumgarte.worst_balance, projection.worst_balance);
}

TEST(EnergyBalance, VerletKeepsEnergyBoundedOverALongRun) {
  // symplectic, second order: the energy error oscillates at O(dt^2) without secular growth.
  // Estimate: E (w dt)^2 with E ~ 20 J and angular speeds w up to ~10 rad/s gives ~2e-3 J at
  // dt = 1e-3; the bound allows five times that, 1e-3 of the 10 J m g L scale
  const RunResult verlet = run("verlet", 1e-3, CorrectionDef::Method::kProjection, 20.0);
  EXPECT_LT(verlet.worst_balance, 1e-2);
  std::printf("double pendulum 20 s verlet dt=1e-3 projection: max |balance| %.3e J\n", verlet.worst_balance);
}

TEST(ConstraintDrift, GrowsWithoutCorrectionAndStaysBoundedWithIt) {
  // RK4 at dt = 5e-3 over 10 s of chaotic motion
  const double end = 10.0, dt = 5e-3;
  const RunResult none = run("rk4", dt, CorrectionDef::Method::kNone, end);
  const RunResult baumgarte = run("rk4", dt, CorrectionDef::Method::kBaumgarte, end);
  const RunResult projection = run("rk4", dt, CorrectionDef::Method::kProjection, end);
  std::printf("drift over %.0f s (rk4, dt=5e-3): none %.3e at 1 s -> %.3e at 10 s, baumgarte max %.3e, "
              "projection max %.3e\n", end, none.drift_early, none.drift_late, baumgarte.worst_drift,
              projection.worst_drift);
  // without correction the violation accumulates: at least a hundredfold from 1 s to 10 s
  EXPECT_GT(none.drift_late, 100.0 * none.drift_early);
  // Baumgarte (alpha = beta = 5) damps violations within ~1/alpha = 0.2 s, i.e. 40 steps of
  // local error ~(w dt)^5 ~ 3e-7: it stays near 1e-5 at most, and far below the uncorrected drift
  EXPECT_LT(baumgarte.worst_drift, 1e-5);
  EXPECT_LT(baumgarte.worst_drift, 0.1 * none.drift_late);
  // projection ends each step within its tolerance 1e-10
  EXPECT_LT(projection.worst_drift, 1e-10);
}

}  // namespace
}  // namespace periflex
