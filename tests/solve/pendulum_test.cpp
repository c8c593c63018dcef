// The point-mass pendulum released from the horizontal against the exact solution:
// period 4 sqrt(L/g) K(m), m = sin^2(theta0 / 2), and angle theta(t) = 2 asin(k sn(K - w t | m)),
// with K and sn from the project's one elliptic-function oracle (src/study/elliptic.h, checked
// against Boost.Math in tests/study/elliptic_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solve/simulation.h"
#include "study/elliptic.h"
#include "test_scenes.h"

namespace periflex {
namespace {

constexpr double kLength = 1.0;
constexpr double kG = 9.81;
constexpr double kTheta0 = kPi / 2;

double exact_angle(double t) {
  const double m = std::pow(std::sin(kTheta0 / 2), 2);
  const double w = std::sqrt(kG / kLength);
  return 2.0 * std::asin(std::sqrt(m) * jacobi_elliptic(elliptic_k(m) - w * t, m).sn);
}

double exact_period() { return 4.0 * std::sqrt(kLength / kG) * elliptic_k(std::pow(std::sin(kTheta0 / 2), 2)); }

// Time at which x of the bob crosses zero downwards, found on the cubic Hermite interpolant of
// (x, vx) between two samples (error O(dt^4)).
double crossing_time(double t0, double x0, double v0, double t1, double x1, double v1) {
  const double h = t1 - t0;
  auto x = [&](double s) {
    const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
    const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
    return h00 * x0 + h10 * h * v0 + h01 * x1 + h11 * h * v1;
  };
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (x(mid) > 0.0 ? lo : hi) = mid;
  }
  return t0 + 0.5 * (lo + hi) * h;
}

// Runs 1.5 periods and returns the time between the first two downward zero crossings of x.
double measured_period(const std::string& integrator, double dt) {
  SceneDef scene = test::point_pendulum(kLength, kTheta0, integrator, dt);
  scene.gravity = Vec2(0.0, -kG);
  scene.solver.rtol = 1e-11;
  scene.solver.atol = 1e-12;
  scene.probes.push_back({"bob", "bob", Vec2::Zero(), {}});
  Simulation sim(scene);
  sim.initialize();
  std::vector<double> crossings;
  Sample last = sim.sample();
  while (sim.time() < 1.6 * exact_period() && crossings.size() < 2) {
    sim.step();
    const Sample now = sim.sample();
    const double x0 = last.probe_values[0], x1 = now.probe_values[0];
    if (x0 > 0.0 && x1 <= 0.0) {
      crossings.push_back(crossing_time(last.time, x0, last.probe_values[2], now.time, x1, now.probe_values[2]));
    }
    last = now;
  }
  EXPECT_EQ(crossings.size(), 2u);
  return crossings.size() == 2 ? crossings[1] - crossings[0] : 0.0;
}

TEST(Pendulum, PeriodMatchesEllipticIntegralRk4) {
  // RK4 at dt = 1e-3 (w dt = 3e-3): phase error ~ (w dt)^4 per radian, far below 1e-6
  const double period = measured_period("rk4", 1e-3);
  EXPECT_NEAR(period / exact_period() - 1.0, 0.0, 1e-6) << "period " << period;
  RecordProperty("period_relative_error_rk4", std::to_string(period / exact_period() - 1.0));
  std::printf("pendulum period (rk4, dt=1e-3): relative error %.3e\n", period / exact_period() - 1.0);
}

TEST(Pendulum, PeriodMatchesEllipticIntegralDopri) {
  // adaptive 5(4) with rtol 1e-11: the global error stays near the tolerance
  const double period = measured_period("dopri54", 1e-2);
  EXPECT_NEAR(period / exact_period() - 1.0, 0.0, 1e-6) << "period " << period;
  std::printf("pendulum period (dopri54, rtol=1e-11): relative error %.3e\n", period / exact_period() - 1.0);
}

TEST(Pendulum, AngleFollowsJacobiEllipticSolutionOverOnePeriod) {
  SceneDef scene = test::point_pendulum(kLength, kTheta0, "rk4", 1e-3);
  scene.gravity = Vec2(0.0, -kG);
  scene.probes.push_back({"bob", "bob", Vec2::Zero(), {}});
  Simulation sim(scene);
  sim.initialize();
  double worst = 0.0;
  const double period = exact_period();
  for (int k = 1; k <= 100; ++k) {
    sim.advance_to(period * k / 100.0);
    const Sample s = sim.sample();
    const double angle = std::atan2(s.probe_values[0], -s.probe_values[1]);
    worst = std::max(worst, std::abs(angle - exact_angle(sim.time())));
  }
  // RK4 global error at dt = 1e-3 over one period is ~1e-10 rad; 1e-8 leaves room for round-off
  EXPECT_LT(worst, 1e-8);
  std::printf("pendulum angle (rk4, dt=1e-3): max error over a period %.3e rad\n", worst);
}

TEST(Pendulum, ZeroInertiaBodyIsDeterminedByItsJoint) {
  Simulation sim(test::point_pendulum(1.0, 0.3, "rk4", 1e-3));
  EXPECT_EQ(sim.info().degrees_of_freedom, 1);
  EXPECT_EQ(sim.info().redundant_equations, 0);
  sim.initialize();
  sim.advance_to(0.5);
  const Sample s = sim.sample();
  EXPECT_TRUE(std::isfinite(s.energies.kinetic));
  EXPECT_GT(s.energies.kinetic, 0.1);  // it swung: m g L (1 - cos 0.3) = 0.44 J available
}

}  // namespace
}  // namespace periflex
