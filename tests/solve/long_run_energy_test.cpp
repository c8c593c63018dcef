// Long runs of a conservative pendulum (a 1 m, 1 kg bar pinned at one end, released
// horizontal; energy scale m g L / 2 = 4.9 J) with each integrator and correction, stepping as
// the program does (Simulation::step). What each combination does is documented in
// docs/solver.md; these tests hold the documented bounds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"
#include "support/sanitizer_build.h"

namespace periflex {
namespace {

// 10^6 steps of 4 ms (4000 s, about 2000 swings) for every integrator and correction; a
// sanitizer build, some twenty times slower, runs the first tenth (the bounds are the same).
#if PERIFLEX_UNDER_SANITIZER
constexpr long kLongRun = 100000;
#else
constexpr long kLongRun = 1000000;
#endif

SceneDef bar_pendulum(const std::string& integrator, double dt, CorrectionDef::Method method) {
  SceneDef s = test::empty_scene(integrator, dt, method);
  s.solver.correction.tolerance = 1e-10;
  s.solver.rtol = 1e-8;
  s.solver.atol = 1e-10;
  s.bodies.push_back(test::body("bar", 1.0, 1.0 / 12.0, Vec2(0.5, 0.0)));
  s.joints.push_back(test::revolute("pin", "ground", "bar", Vec2::Zero(), Vec2(-0.5, 0.0)));
  return s;
}

struct LongRun {
  double early = 0.0, late = 0.0;  // max |balance| over the first and the second half
  double gained = -1e300;          // max balance (signed): energy the run made
  bool stopped = false;            // a NumericalError ended the run
  double seconds = 0.0;
};

LongRun run(const std::string& integrator, CorrectionDef::Method method, double dt, long steps) {
  Simulation sim(bar_pendulum(integrator, dt, method));
  sim.initialize();
  LongRun r;
  const auto start = std::chrono::steady_clock::now();
  try {
    for (long k = 1; k <= steps; ++k) {
      sim.step();
      if (k % 100 != 0) continue;
      const double signed_balance = sim.sample().energies.balance;
      r.gained = std::max(r.gained, signed_balance);
      const double b = std::abs(signed_balance);
      (k <= steps / 2 ? r.early : r.late) = std::max(k <= steps / 2 ? r.early : r.late, b);
    }
  } catch (const NumericalError&) {
    r.stopped = true;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-17s %-10s dt %g, %ld steps: max |balance| %.3g J (first half), %.3g J (second half)%s, %.2f s\n",
              integrator.c_str(), method == CorrectionDef::Method::kProjection  ? "projection"
                                  : method == CorrectionDef::Method::kBaumgarte ? "baumgarte"
                                                                                 : "none",
              dt, steps, r.early, r.late, r.stopped ? ", stopped" : "", r.seconds);
  return r;
}

// Symplectic Euler and Verlet with projection (SHAKE on positions, RATTLE on velocities) over
// 10^6 steps of 4 ms (4000 s, about 2000 swings): the balance stays bounded.
// Before, symplectic Euler with projection gained energy exponentially and stopped at 31 s.
TEST(LongRunEnergy, SymplecticIntegratorsWithProjectionStayBounded) {
  for (const std::string integrator : {"symplectic_euler", "verlet"}) {
    const LongRun r = run(integrator, CorrectionDef::Method::kProjection, 0.004, kLongRun);
    EXPECT_FALSE(r.stopped) << integrator;
    EXPECT_LT(r.late, 0.1) << integrator;
    // symplectic Euler: the error oscillates with a fixed amplitude. Verlet's closing half
    // kick uses the force at the positions before their projection, so it keeps a slow drift
    // (0.023 J after 2000 s, 0.047 J after 4000 s; docs/solver.md) and is not held to this
    if (integrator == "symplectic_euler") {
      EXPECT_LT(r.late, 1.5 * r.early + 1e-9) << "the energy error grows";
    }
  }
}

// RK4 and dopri54 with projection: not symplectic, the balance drifts by the local error,
// far below the bound over 10^6 steps (4.5e-6 J for rk4, 8e-9 J for dopri54).
TEST(LongRunEnergy, RungeKuttaWithProjectionDriftsByTheLocalError) {
  for (const std::string integrator : {"rk4", "dopri54"}) {
    const LongRun r = run(integrator, CorrectionDef::Method::kProjection, 0.004, kLongRun);
    EXPECT_FALSE(r.stopped) << integrator;
    EXPECT_LT(r.late, 1e-4) << integrator;
  }
}

// Baumgarte and no correction: what they do over 10^6 steps, as the docs say. With the
// symplectic integrators the stabilisation terms do work and the constraint drifts: the run
// either keeps its balance under 10 % of the energy scale or stops with a NumericalError,
// never NaN; with rk4 Baumgarte holds the balance.
TEST(LongRunEnergy, BaumgarteAndNoCorrectionAreBoundedOrStopped) {
  for (const std::string integrator : {"symplectic_euler", "verlet", "rk4"}) {
    for (auto method : {CorrectionDef::Method::kBaumgarte, CorrectionDef::Method::kNone}) {
      const LongRun r = run(integrator, method, 0.004, kLongRun);
      if (!r.stopped) {
        EXPECT_LT(r.late, 0.49) << integrator;
      }
    }
  }
  EXPECT_LT(run("rk4", CorrectionDef::Method::kBaumgarte, 0.004, kLongRun).late, 1e-3);
}

// HHT-alpha (alpha = -0.1) over 10^6 steps: its numerical damping takes energy out slowly and
// never puts any in (the balance stays at or below round-off); with projection it loses 0.13 J
// of the 4.9 J by 4000 s (0.066 J at half-way), with Baumgarte 2.2 J (1.4 J at half-way);
// without correction it drifts off the constraint and stops. The bounds on the loss are those
// figures with a margin of about 1.5 (docs/solver.md); never gaining is the property held.
TEST(LongRunEnergy, HhtDampsEnergyAndNeverGainsIt) {
  const LongRun projected = run("hht", CorrectionDef::Method::kProjection, 0.004, kLongRun);
  EXPECT_FALSE(projected.stopped);
  EXPECT_LT(projected.gained, 1e-9);
  EXPECT_LT(projected.late, 0.2);
  EXPECT_GT(projected.late, projected.early) << "numerical damping removes energy as the run goes";
  const LongRun stabilised = run("hht", CorrectionDef::Method::kBaumgarte, 0.004, kLongRun);
  EXPECT_FALSE(stabilised.stopped);
  EXPECT_LT(stabilised.gained, 1e-9);
  EXPECT_LT(stabilised.late, 3.0);
  const LongRun free = run("hht", CorrectionDef::Method::kNone, 0.004, kLongRun);
  if (!free.stopped) {
    EXPECT_LT(free.late, 0.49);
  }
}

// dopri54 (rtol 1e-8) with Baumgarte and without correction over 10^6 steps: Baumgarte holds
// the balance near the tolerance (7e-8 J); without correction the drift grows as t^2 (6e-6 J at
// half-way, 2.4e-5 J at 4000 s) but stays small.
TEST(LongRunEnergy, DormandPrinceWithBaumgarteOrNoCorrectionDriftsByTheTolerance) {
  const LongRun stabilised = run("dopri54", CorrectionDef::Method::kBaumgarte, 0.004, kLongRun);
  EXPECT_FALSE(stabilised.stopped);
  EXPECT_LT(stabilised.late, 1e-6);
  const LongRun free = run("dopri54", CorrectionDef::Method::kNone, 0.004, kLongRun);
  EXPECT_FALSE(free.stopped);
  EXPECT_LT(free.late, 1e-4);
}

}  // namespace
}  // namespace periflex
