// The elliptic functions behind the exact pendulum, against published values, identities and
// Boost.Math evaluated in 50-digit arithmetic (an independent implementation, libboost-dev).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

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

// Boost.Math at 50 digits is the truth here. It is given the parameter the code sees, m as a
// double, so its modulus is sqrt(m) to 50 digits and the rounding of k^2 is no error of ours.
using Big = boost::multiprecision::cpp_bin_float_50;
constexpr double kEps = std::numeric_limits<double>::epsilon();
const double kModuli[] = {0.0, 0.1, 0.3, 0.5, 0.7071067811865476, 0.9, 0.99, 0.999};

TEST(Elliptic, CompleteIntegralMatchesBoostMath) {
  for (const double k : kModuli) {
    const double m = k * k;
    const double exact = static_cast<double>(boost::math::ellint_1(boost::multiprecision::sqrt(Big(m))));
    // the AGM converges quadratically and each round costs one rounding: 4 eps relative is a
    // margin over the 1 ulp measured (K grows to 4.8 at k = 0.999)
    EXPECT_NEAR(elliptic_k(m), exact, 4.0 * kEps * exact) << "k = " << k;
  }
}

TEST(Elliptic, JacobiFunctionsMatchBoostMathOverSeveralPeriods) {
  for (const double k : kModuli) {
    const double m = k * k;
    const Big modulus = boost::multiprecision::sqrt(Big(m));
    const double period = 4.0 * elliptic_k(m);
    // from one period back to four ahead, at a spacing no fraction of the period (so the samples
    // fall near the zeros of cn as well as on them)
    double worst = 0.0;
    for (int i = -40; i <= 160; ++i) {
      const double u = i * (period / 40.0 + 1e-3);
      Big cn, dn;
      const Big sn = boost::math::jacobi_elliptic(modulus, Big(u), &cn, &dn);
      const JacobiValues v = jacobi_elliptic(u, m);
      const double error = std::max({std::abs(v.sn - static_cast<double>(sn)), std::abs(v.cn - static_cast<double>(cn)),
                                     std::abs(v.dn - static_cast<double>(dn))});
      // The amplitude starts as 2^N a_N u, rounded to a relative eps: an absolute error of
      // about eps |u| in am(u), which sn, cn and dn pass on with slope at most 1, plus a few
      // roundings in the N descending steps. Measured: at most 1.8 eps (1 + |u|) on this grid.
      EXPECT_LE(error, 4.0 * kEps * (1.0 + std::abs(u))) << "k = " << k << ", u = " << u;
      worst = std::max(worst, error / (kEps * (1.0 + std::abs(u))));
    }
    RecordProperty("worst_over_eps_k" + std::to_string(k), std::to_string(worst));
  }
}

TEST(Elliptic, JacobiFunctionsMatchBoostMathAtTheA01Arguments) {
  // The IFToMM A01 pendulum over 2000 s: m = 1/2, u = omega0 t up to 6264 (about 850 swings).
  // Same bound as above: there the error is eps |u|, 1.4e-12 at the end, carried by the argument.
  const double m = 0.5;
  const Big modulus = boost::multiprecision::sqrt(Big(m));
  const double omega0 = std::sqrt(9.81);
  for (int i = 1; i <= 400; ++i) {
    const double u = omega0 * 5.0 * i + 1e-3 * i;
    Big cn, dn;
    const Big sn = boost::math::jacobi_elliptic(modulus, Big(u), &cn, &dn);
    const JacobiValues v = jacobi_elliptic(u, m);
    EXPECT_NEAR(v.sn, static_cast<double>(sn), 4.0 * kEps * (1.0 + u)) << "u = " << u;
    EXPECT_NEAR(v.cn, static_cast<double>(cn), 4.0 * kEps * (1.0 + u)) << "u = " << u;
    EXPECT_NEAR(v.dn, static_cast<double>(dn), 4.0 * kEps * (1.0 + u)) << "u = " << u;
  }
}

}  // namespace
}  // namespace periflex
