// Complete elliptic integral of the first kind and the Jacobi elliptic functions, computed by
// the arithmetic-geometric mean (Abramowitz & Stegun 17.6 and 16.4). They give the exact motion
// of the large-amplitude pendulum that the work-precision studies measure errors against.
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
