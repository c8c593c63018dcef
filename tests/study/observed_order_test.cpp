// Observed order of every integrator on the large-amplitude pendulum, measured by the study
// runner against the exact (Jacobi elliptic) motion: the slope of log error against log dt
// must lie within +-0.3 of the theoretical order.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "study/study_def.h"
#include "study/study_runner.h"

namespace periflex {
namespace {

// A study of one integrator on the pendulum scene of scenes/studies/models/.
StudyResult pendulum_study(const std::string& method_block) {
  const std::string text = std::string(R"(
[study]
scene = ")") + PERIFLEX_SOURCE_ROOT + R"(/scenes/studies/models/pendulum.toml"
reference = "pendulum_exact"
end_time = 1.0
compare_interval = 0.05
)" + method_block;
  return run_study(parse_study(text, "observed_order_test.toml"));
}

const ObservedOrder& only_order(const StudyResult& r) {
  EXPECT_EQ(r.orders.size(), 1u);
  for (const StudyRow& row : r.rows) {
    EXPECT_TRUE(row.ok()) << row.status;
    // the series, for the log when an order is off
    std::printf("  %s dt=%g tol=%g error=%g\n", row.integrator.c_str(), row.dt, row.tol, row.error_max_rel);
  }
  return r.orders.front();
}

// +-0.3 around theory, as the study asks; the steps are chosen in each method's asymptotic range
// and above round-off.
constexpr double kOrderTolerance = 0.3;

TEST(ObservedOrder, SymplecticEulerIsFirstOrder) {
  const auto r = pendulum_study(R"(
[[method]]
integrator = "symplectic_euler"
dt = [2e-3, 1e-3, 5e-4, 2.5e-4]
correction = "projection"
)");
  EXPECT_NEAR(only_order(r).slope, 1.0, kOrderTolerance);
}

TEST(ObservedOrder, VerletIsSecondOrder) {
  const auto r = pendulum_study(R"(
[[method]]
integrator = "verlet"
dt = [2e-3, 1e-3, 5e-4, 2.5e-4]
correction = "projection"
)");
  EXPECT_NEAR(only_order(r).slope, 2.0, kOrderTolerance);
}

TEST(ObservedOrder, RungeKutta4IsFourthOrder) {
  const auto r = pendulum_study(R"(
[[method]]
integrator = "rk4"
dt = [1e-2, 5e-3, 2.5e-3]
correction = "none"
)");
  EXPECT_NEAR(only_order(r).slope, 4.0, kOrderTolerance);
}

TEST(ObservedOrder, DormandPrinceAtFixedStepsIsFifthOrder) {
  // tolerances so loose that every internal step is accepted at the full dt: fixed-step DP5
  const auto r = pendulum_study(R"(
[[method]]
integrator = "dopri54"
dt = [1.25e-2, 6.25e-3, 3.125e-3]
tol = 1e10
correction = "none"
)");
  const ObservedOrder& o = only_order(r);
  EXPECT_FALSE(o.against_tolerance);
  EXPECT_NEAR(o.slope, 5.0, kOrderTolerance);
}

TEST(ObservedOrder, DormandPrinceAdaptiveErrorIsProportionalToTolerance) {
  // error-per-step control of a 4th-order estimate with 5th-order propagation: global error ~ tol^1
  const auto r = pendulum_study(R"(
[[method]]
integrator = "dopri54"
dt = [5e-2]
tol = [1e-6, 1e-7, 1e-8, 1e-9]
correction = "none"
)");
  const ObservedOrder& o = only_order(r);
  EXPECT_TRUE(o.against_tolerance);
  EXPECT_NEAR(o.slope, 1.0, kOrderTolerance);
}

TEST(ObservedOrder, HhtIsSecondOrder) {
  const auto r = pendulum_study(R"(
[[method]]
integrator = "hht"
dt = [2e-3, 1e-3, 5e-4, 2.5e-4]
correction = "projection"
)");
  EXPECT_NEAR(only_order(r).slope, 2.0, kOrderTolerance);
}

}  // namespace
}  // namespace periflex
