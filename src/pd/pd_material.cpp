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

double cell_fraction_in_disc(int a, int b, double m) {
  // midpoint rule across the cell in x; in y the chord of the disc is cut exactly
  constexpr int kSamples = 512;
  double area = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double x = a - 0.5 + (k + 0.5) / kSamples;
    if (std::abs(x) >= m) continue;
    const double half_chord = std::sqrt(m * m - x * x);
    const double lo = std::max(b - 0.5, -half_chord), hi = std::min(b + 0.5, half_chord);
    if (hi > lo) area += (hi - lo) / kSamples;
  }
  return area;
}

double implied_poisson_ratio(bool plane_strain) { return plane_strain ? 0.25 : 1.0 / 3.0; }

}  // namespace periflex
