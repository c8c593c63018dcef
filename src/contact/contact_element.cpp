#include "contact/contact_element.h"

#include <cmath>

#include "core/vec2.h"

namespace periflex {

double damping_ratio(double restitution) {
  if (restitution >= 1.0) return 0.0;
  const double log_e = std::log(restitution);
  return -log_e / std::sqrt(kPi * kPi + log_e * log_e);
}

double damped_step(double undamped_step, double zeta) {
  return undamped_step * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

}  // namespace periflex
