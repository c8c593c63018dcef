// The elliptic functions behind the exact pendulum, against published values and identities.
#include <gtest/gtest.h>

#include <cmath>

#include "core/vec2.h"
#include "study/elliptic.h"

namespace periflex {
namespace {

TEST(Elliptic, CompleteIntegralMatchesTabulatedValues) {
  // Abramowitz & Stegun table 17.1 values, printed to 15 digits; the AGM converges to round-off.
  EXPECT_NEAR(elliptic_k(0.0), kPi / 2.0, 1e-15);
  EXPECT_NEAR(elliptic_k(0.5), 1.854074677301372, 1e-14);
  EXPECT_NEAR(elliptic_k(0.9), 2.578092113348173, 1e-14);
}

TEST(Elliptic, JacobiFunctionsAtQuarterPeriodAndLimits) {
  const double m = 0.7;
  const JacobiValues at_k = jacobi_elliptic(elliptic_k(m), m);
  // sn(K) = 1, cn(K) = 0, dn(K) = sqrt(1 - m); 1e-12 covers the round-off of K and the AGM
  EXPECT_NEAR(at_k.sn, 1.0, 1e-12);
  EXPECT_NEAR(at_k.cn, 0.0, 1e-7);  // cn near its zero is sqrt-sensitive to the last bit of K
  EXPECT_NEAR(at_k.dn, std::sqrt(1.0 - m), 1e-12);
  // m = 0: circular functions
  const JacobiValues circ = jacobi_elliptic(0.8, 0.0);
  EXPECT_NEAR(circ.sn, std::sin(0.8), 1e-15);
  EXPECT_NEAR(circ.cn, std::cos(0.8), 1e-15);
  // near m = 1: sn -> tanh, cn -> sech (A&S 16.15), to O(1 - m)
  const JacobiValues hyp = jacobi_elliptic(0.6, 1.0 - 1e-12);
  EXPECT_NEAR(hyp.sn, std::tanh(0.6), 1e-10);
  EXPECT_NEAR(hyp.cn, 1.0 / std::cosh(0.6), 1e-10);
}

TEST(Elliptic, JacobiFunctionsSatisfyIdentitiesAndTheDifferentialEquation) {
  const double m = 0.45, u = 1.3, h = 1e-5;
  const JacobiValues v = jacobi_elliptic(u, m);
  EXPECT_NEAR(v.sn * v.sn + v.cn * v.cn, 1.0, 1e-14);
  // d sn / du = cn dn, by a central difference (truncation ~ h^2 = 1e-10)
  const double derivative = (jacobi_elliptic(u + h, m).sn - jacobi_elliptic(u - h, m).sn) / (2.0 * h);
  EXPECT_NEAR(derivative, v.cn * v.dn, 1e-9);
  // period 4K
  const double k4 = 4.0 * elliptic_k(m);
  EXPECT_NEAR(jacobi_elliptic(u + k4, m).sn, v.sn, 1e-12);
}

}  // namespace
}  // namespace periflex
