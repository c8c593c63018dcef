// The HHT-alpha integrator on small systems with known answers, driven directly through the
// integrator interface: second-order convergence on the large-amplitude pendulum, unconditional
// stability on a stiff spring chain, its iteration matrices kept when output times shorten
// steps, and a clear failure when Newton cannot converge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/vec2.h"
#include "solve/integrator_hht.h"
#include "study/elliptic.h"

namespace periflex {
namespace {

// theta'' = -w2 sin(theta): the pendulum in its angle.
class AnglePendulum final : public OdeSystem {
 public:
  explicit AnglePendulum(double w2) : w2_(w2) {}
  void derivative(double, const Eigen::VectorXd& q, const Eigen::VectorXd&, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    qdd.resize(1);
    qdd[0] = -w2_ * std::sin(q[0]);
    power.setZero();
  }

 private:
  double w2_;
};

double pendulum_error(double theta0, double w2, double end, double h) {
  AnglePendulum system(w2);
  auto hht = make_hht(kDefaultHhtAlpha);
  OdeState s;
  s.q = Eigen::VectorXd::Constant(1, theta0);
  s.qd = Eigen::VectorXd::Zero(1);
  const long steps = std::lround(end / h);
  // largest error over the run against the exact sin(theta / 2) = k cd(w t | k^2)
  const double k = std::sin(0.5 * theta0);
  double worst = 0.0;
  for (long n = 0; n < steps; ++n) {
    hht->step(system, n * h, h, s);
    const JacobiValues j = jacobi_elliptic(std::sqrt(w2) * (n + 1) * h, k * k);
    worst = std::max(worst, std::abs(s.q[0] - 2.0 * std::asin(k * j.cn / j.dn)));
  }
  return worst;
}

TEST(IntegratorHht, SecondOrderOnTheLargeAmplitudePendulum) {
  const double e1 = pendulum_error(2.0, 9.81, 2.0, 0.01);
  const double e2 = pendulum_error(2.0, 9.81, 2.0, 0.005);
  const double e3 = pendulum_error(2.0, 9.81, 2.0, 0.0025);
  const double order_a = std::log2(e1 / e2), order_b = std::log2(e2 / e3);
  // theory: 2; +-0.3 allows the pre-asymptotic part of the largest step
  EXPECT_NEAR(order_a, 2.0, 0.3);
  EXPECT_NEAR(order_b, 2.0, 0.3);
  // error constant of HHT (alpha = -0.1) on this swing: about 5 (omega h)^2 rad, so well below 1e-3 at h = 2.5e-3
  EXPECT_LT(e3, 1e-3);
}

// A chain of unit masses joined by springs of stiffness k, fixed at one end: stiff, linear.
class SpringChain final : public OdeSystem {
 public:
  SpringChain(int n, double k) : n_(n), k_(k) {}
  void derivative(double, const Eigen::VectorXd& q, const Eigen::VectorXd&, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    ++evaluations;
    qdd.setZero(n_);
    for (int i = 0; i < n_; ++i) {
      const double left = i == 0 ? 0.0 : q[i - 1];
      qdd[i] -= k_ * (q[i] - left);
      if (i + 1 < n_) qdd[i] -= k_ * (q[i] - q[i + 1]);
    }
    power.setZero();
  }
  double energy(const OdeState& s) const {
    double e = 0.5 * s.qd.squaredNorm();
    for (int i = 0; i < n_; ++i) {
      const double left = i == 0 ? 0.0 : s.q[i - 1];
      e += 0.5 * k_ * (s.q[i] - left) * (s.q[i] - left);
    }
    return e;
  }
  int evaluations = 0;

 private:
  int n_;
  double k_;
};

TEST(IntegratorHht, StableFarAboveTheExplicitCriticalStep) {
  const int n = 40;
  const double k = 1e6;
  SpringChain chain(n, k);
  // highest frequency of the chain < 2 sqrt(k): the explicit (central difference) limit is 2 / w_max
  const double critical = 2.0 / (2.0 * std::sqrt(k));
  for (double factor : {10.0, 100.0}) {
    auto hht = make_hht(kDefaultHhtAlpha);
    OdeState s;
    s.q = Eigen::VectorXd::Zero(n);
    s.qd = Eigen::VectorXd::Zero(n);
    s.q[n - 1] = 1e-3;  // pluck the free end
    const double e0 = chain.energy(s);
    const double h = factor * critical;
    for (int step = 0; step < 400; ++step) hht->step(chain, step * h, h, s);
    // HHT never adds energy to a linear system; numerical damping only removes it
    EXPECT_LE(chain.energy(s), e0 * (1.0 + 1e-9)) << "factor " << factor;
    EXPECT_LT(chain.energy(s), 0.999 * e0) << "factor " << factor << ": alpha < 0 damps the plucked end's fast modes";
    EXPECT_TRUE(s.q.allFinite());
    // alpha = 0 is the trapezoidal rule, which keeps a linear system's energy at any step (to
    // the Newton tolerance; 1e-14 of it measured): the same run, bounded from both sides
    auto trapezoidal = make_hht(0.0);
    OdeState u;
    u.q = Eigen::VectorXd::Zero(n);
    u.qd = Eigen::VectorXd::Zero(n);
    u.q[n - 1] = 1e-3;
    for (int step = 0; step < 400; ++step) trapezoidal->step(chain, step * h, h, u);
    EXPECT_NEAR(chain.energy(u), e0, 1e-12 * e0) << "factor " << factor;
  }
}

// A run lands on its output times by shortening the step before each: with outputs every 2.5
// steps it alternates h, h, h/2. The iteration matrices of both step sizes are kept, so a step
// of this linear system costs four evaluations once each matrix is built (three Newton
// iterates, the finite-difference matrix being exact only to round-off, and the end);
// rebuilding the matrix at every change of step size cost two more a step on average (three
// colours at two of every three steps).
TEST(IntegratorHht, KeepsTheMatricesOfBothStepSizesWhenOutputTimesShortenSteps) {
  const int n = 40;
  const double k = 1e6;
  SpringChain chain(n, k);
  auto hht = make_hht(kDefaultHhtAlpha);
  OdeState s;
  s.q = Eigen::VectorXd::Zero(n);
  s.qd = Eigen::VectorXd::Zero(n);
  s.q[n - 1] = 1e-3;
  const double h = 10.0 * 2.0 / (2.0 * std::sqrt(k)), interval = 2.5 * h;
  double t = 0.0;
  int steps = 0;
  for (int output = 1; output <= 100; ++output) {
    const double target = output * interval;
    while (t < target - 1e-9 * h) {
      const double step = std::min(h, target - t);
      hht->step(chain, t, step, s);
      t += step;
      ++steps;
    }
  }
  ASSERT_EQ(steps, 300);
  // the pattern found once by perturbing each coordinate (40), two matrices of three colours
  EXPECT_LE(chain.evaluations, 4 * steps + n + 2 * 3 + 20) << chain.evaluations << " evaluations in " << steps << " steps";
  EXPECT_TRUE(s.q.allFinite());
}

// Acceleration that jumps with the position: Newton cannot converge on it.
class Discontinuous final : public OdeSystem {
 public:
  void derivative(double, const Eigen::VectorXd& q, const Eigen::VectorXd&, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    qdd.resize(1);
    qdd[0] = q[0] > 0.0 ? -1e12 : 1e12;
    power.setZero();
  }
};

TEST(IntegratorHht, NewtonFailureNamesResidualStepAndRemedy) {
  Discontinuous system;
  auto hht = make_hht(kDefaultHhtAlpha);
  OdeState s;
  s.q = Eigen::VectorXd::Constant(1, 1e-3);
  s.qd = Eigen::VectorXd::Zero(1);
  try {
    for (int k = 0; k < 10; ++k) hht->step(system, k * 0.1, 0.1, s);
    FAIL() << "expected a NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.diagnostic().quantity, "Newton residual");
    EXPECT_GE(e.diagnostic().step, 1);
    EXPECT_NE(e.diagnostic().remedy.find("solver.dt"), std::string::npos);
  }
}

// A system whose constraints cannot be solved away from the start: |q| > 0.5 throws as the
// constraint solve does at a toggle position. The step is far too large for Newton, whose
// iterates overshoot into that region; the start and the answer lie well inside it.
class SingularAwayFromTheStart final : public OdeSystem {
 public:
  void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd&, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    if (std::abs(q[0]) > 0.5)
      throw NumericalError({"constraint Jacobian", -1, t, "the constraint Jacobian is singular", "change the geometry"});
    qdd.resize(1);
    qdd[0] = -1e6 * q[0] - 1e9 * q[0] * q[0] * q[0];
    power.setZero();
  }
};

// A Newton iterate the system cannot evaluate is a step too large, not a singular mechanism:
// the failure says so and asks for a smaller step.
TEST(IntegratorHht, UnsolvableNewtonIterateAsksForASmallerStep) {
  SingularAwayFromTheStart system;
  auto hht = make_hht(kDefaultHhtAlpha);
  OdeState s;
  s.q = Eigen::VectorXd::Constant(1, 0.1);
  s.qd = Eigen::VectorXd::Zero(1);
  // a step Newton can take: the oscillation stays inside the region the system evaluates
  OdeState small = s;
  for (int k = 0; k < 100; ++k) hht->step(system, k * 1e-4, 1e-4, small);
  EXPECT_LE(std::abs(small.q[0]), 0.1 + 1e-9);
  hht = make_hht(kDefaultHhtAlpha);
  try {
    hht->step(system, 0.0, 1.0, s);
    FAIL() << "expected a NumericalError, q = " << s.q[0];
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.diagnostic().quantity, "Newton residual") << e.what();
    EXPECT_NE(e.diagnostic().cause.find("constraint Jacobian is singular"), std::string::npos) << e.what();
    EXPECT_NE(e.diagnostic().remedy.find("lower solver.dt"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace periflex
