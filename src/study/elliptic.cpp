#include "study/elliptic.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "core/vec2.h"

namespace periflex {

double elliptic_k(double m) {
  if (!(m >= 0.0 && m < 1.0)) throw std::domain_error("elliptic_k: parameter m outside [0, 1)");
  // the AGM of 1 and sqrt(1 - m) converges quadratically; K = pi / (2 AGM)
  double a = 1.0, b = std::sqrt(1.0 - m);
  for (int n = 0; n < 60 && std::abs(a - b) > 1e-16 * a; ++n) {
    const double next_a = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next_a;
  }
  return kPi / (2.0 * a);
}

JacobiValues jacobi_elliptic(double u, double m) {
  if (!(m >= 0.0 && m < 1.0)) throw std::domain_error("jacobi_elliptic: parameter m outside [0, 1)");
  if (m < 1e-300) return {std::sin(u), std::cos(u), 1.0};
  // descending AGM sequence a_n, c_n (A&S 16.4.3) ...
  constexpr int kMax = 40;
  std::array<double, kMax + 1> a{}, c{};
  a[0] = 1.0;
  double b = std::sqrt(1.0 - m);
  c[0] = std::sqrt(m);
  int n = 0;
  while (n < kMax && std::abs(c[n]) > 1e-16) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  // ... then the amplitude phi_N = 2^N a_N u, carried back to phi_0 = am(u | m)
  double phi = std::ldexp(a[n] * u, n);
  for (int j = n; j > 0; --j) phi = 0.5 * (phi + std::asin(c[j] / a[j] * std::sin(phi)));
  JacobiValues v;
  v.sn = std::sin(phi);
  v.cn = std::cos(phi);
  // dn > 0 for m < 1, so the identity dn^2 = 1 - m sn^2 fixes it without cancellation trouble
  v.dn = std::sqrt(1.0 - m * v.sn * v.sn);
  return v;
}

}  // namespace periflex
