// A made-up plot history for the plot tests: n rows of t = k / 10, driver_work = k,
// fracture = -2 k and a flat probe.tip.y = 0.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/plot_history.h"

namespace periflex::testing {

inline PlotHistory two_series(int n) {
  auto columns = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"t", "driver_work", "fracture", "probe.tip.y"});
  PlotHistory h(100);
  for (int k = 0; k < n; ++k) {
    Snapshot s;
    s.step = k;
    s.time = 0.1 * k;
    s.series_columns = columns;
    s.series = {s.time, double(k), -2.0 * k, 0.0};
    h.add(s, 0.0);
  }
  return h;
}

}  // namespace periflex::testing
