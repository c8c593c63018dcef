#include "contact/contact_stiffness.h"

#include <algorithm>

namespace periflex {

double default_contact_stiffness(const PdBody& flex) {
  const auto& volumes = flex.volumes();
  const double v = volumes.empty() ? 0.0 : *std::max_element(volumes.begin(), volumes.end());
  return 15.0 * flex.micromodulus() * v * v / flex.horizon();
}

}  // namespace periflex
