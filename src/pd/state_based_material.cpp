#include "pd/state_based_material.h"

#include <cmath>

namespace periflex {

double lps_shear_modulus(double e, double nu) { return e / (2.0 * (1.0 + nu)); }

double lps_bulk_modulus(double e, double nu, bool plane_strain) {
  return plane_strain ? e / (2.0 * (1.0 + nu) * (1.0 - 2.0 * nu)) : e / (2.0 * (1.0 - nu));
}

double lps_critical_stretch_from_energy(double g0, double e, double nu, double delta, bool plane_strain,
                                        FlexBodyDef::Influence kind) {
  const double mu = lps_shear_modulus(e, nu), kappa = lps_bulk_modulus(e, nu, plane_strain);
  const double stiffness = 6.0 * mu / kPi + 16.0 * (kappa - 2.0 * mu) / (9.0 * kPi * kPi);
  const double base = std::sqrt(g0 / (stiffness * delta));
  return kind == FlexBodyDef::Influence::kConical ? base * std::sqrt(1.2) : base;
}

}  // namespace periflex
