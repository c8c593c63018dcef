// Complete elliptic integral of the first kind and the Jacobi elliptic functions, computed by
// the arithmetic-geometric mean (Abramowitz & Stegun 17.6 and 16.4). They give the exact motion
// of the large-amplitude pendulum that the work-precision studies and the tests measure errors
// against; this is the project's one implementation.
//
// Kept over Boost.Math (boost::math::jacobi_elliptic, ellint_1) because it measured better
// for this use (all measured against Boost.Math at 50 digits, as tests/study/elliptic_test.cpp
// checks this code):
// - moduli 0 to 0.999, four periods: here at most 1.8 eps (1 + |u|); Boost in double, with its
//   default promotion to long double, up to 126 eps near the zeros of cn, and 2.4e-6 relative
//   (6.6e-11) there without the promotion;
// - the A01 reference over 2000 s (u up to 6264): bob position within 4.0e-12 m here, 2.4e-13 m
//   with Boost's default policy, 3.5e-12 m without promotion; all far below the 4.5e-9 m of
//   the most accurate A01 run in docs/work_precision.md;
// - speed on those 400 000 A01 samples: about 0.9 us per call here, 7 times that with Boost's
//   default policy, the same without promotion (2 shared cores, one thread).
#pragma once

namespace periflex {

// K(m) = int_0^{pi/2} (1 - m sin^2 t)^{-1/2} dt, parameter m = k^2 in [0, 1).
double elliptic_k(double m);

// sn(u | m), cn(u | m), dn(u | m) for m in [0, 1).
struct JacobiValues {
  double sn = 0.0, cn = 1.0, dn = 1.0;
};
JacobiValues jacobi_elliptic(double u, double m);

}  // namespace periflex
