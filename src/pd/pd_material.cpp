#include "pd/pd_material.h"

#include <algorithm>
#include <cmath>

namespace periflex {

double micromodulus(double e, double t, double delta, bool plane_strain) {
  const double d3 = delta * delta * delta;
  return plane_strain ? 48.0 * e / (5.0 * kPi * t * d3) : 9.0 * e / (kPi * t * d3);
}

double influence(FlexBodyDef::Influence kind, double r, double delta) {
  if (kind == FlexBodyDef::Influence::kConstant) return 1.0;
  return r < delta ? 4.0 * (1.0 - r / delta) : 0.0;
}

double critical_stretch_from_energy(double g0, double e, double delta, bool plane_strain,
                                    FlexBodyDef::Influence kind) {
  // G0 = c s0^2 t delta^4 / 4 (constant w) with c from micromodulus(); t cancels
  const double base = plane_strain ? std::sqrt(5.0 * kPi * g0 / (12.0 * e * delta))
                                   : std::sqrt(4.0 * kPi * g0 / (9.0 * e * delta));
  // conical: int w r^3 dr = delta^4 / 5 instead of delta^4 / 4
  return kind == FlexBodyDef::Influence::kConical ? base * std::sqrt(1.25) : base;
}

double isotropic_energy_density(double c, double t, double delta, double eps) {
  return kPi * c * t * delta * delta * delta * eps * eps / 6.0;
}

double uniaxial_strain_energy_density(double c, double t, double delta, double eps) {
  return kPi * c * t * delta * delta * delta * eps * eps / 16.0;
}

double uniaxial_stress_energy_density(double c, double t, double delta, double eps) {
  return kPi * c * t * delta * delta * delta * eps * eps / 18.0;
}

namespace {

// Area of the disc of radius m about the origin inside the rectangle [0, x] x [0, y], x, y >= 0:
// the integral over u in [0, min(x, m)] of min(y, sqrt(m^2 - u^2)), in closed form with
// g(u) = integral_0^u sqrt(m^2 - t^2) dt = (u sqrt(m^2 - u^2) + m^2 asin(u / m)) / 2.
double quadrant_area(double x, double y, double m) {
  if (x <= 0.0 || y <= 0.0) return 0.0;
  if (x * x + y * y <= m * m) return x * y;
  const auto g = [m](double u) { return 0.5 * (u * std::sqrt(std::max(0.0, m * m - u * u)) + m * m * std::asin(u / m)); };
  const double xe = std::min(x, m);
  // below u = sqrt(m^2 - y^2) the rectangle's top edge is inside the disc
  const double u_top = y < m ? std::sqrt(m * m - y * y) : 0.0;
  return y * u_top + g(xe) - g(u_top);
}

// The same for any corner (x, y): signed by quadrant, so that rectangles follow by inclusion
// and exclusion of their four corners.
double corner_area(double x, double y, double m) {
  const double sign = (x < 0.0) != (y < 0.0) ? -1.0 : 1.0;
  return sign * quadrant_area(std::abs(x), std::abs(y), m);
}

}  // namespace

double cell_fraction_in_disc(double a, double b, double m) {
  // the exact area of the unit cell [a - 1/2, a + 1/2] x [b - 1/2, b + 1/2] inside the disc
  const double x0 = a - 0.5, x1 = a + 0.5, y0 = b - 0.5, y1 = b + 0.5;
  const double area = corner_area(x1, y1, m) - corner_area(x0, y1, m) - corner_area(x1, y0, m) + corner_area(x0, y0, m);
  return std::clamp(area, 0.0, 1.0);
}

double implied_poisson_ratio(bool plane_strain) { return plane_strain ? 0.25 : 1.0 / 3.0; }

}  // namespace periflex
