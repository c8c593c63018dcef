#include "study/study_result.h"

#include <cmath>
#include <map>
#include <utility>

namespace periflex {

std::vector<ObservedOrder> observed_orders(const std::vector<StudyRow>& rows, double floor) {
  // group the rows into series in the order they first appear
  std::vector<std::pair<std::string, std::string>> keys;
  std::map<std::pair<std::string, std::string>, std::vector<const StudyRow*>> series;
  for (const StudyRow& row : rows) {
    const auto key = std::make_pair(row.integrator, row.correction);
    if (!series.count(key)) keys.push_back(key);
    series[key].push_back(&row);
  }

  std::vector<ObservedOrder> out;
  for (const auto& key : keys) {
    ObservedOrder order;
    order.integrator = key.first;
    order.correction = key.second;
    order.theory = theoretical_order(key.first);
    // adaptive series that vary the tolerance are measured against it; all others against the step
    for (const StudyRow* row : series[key])
      if (row->tol != series[key].front()->tol) order.against_tolerance = true;
    // an adaptive pair's global error follows the tolerance to the first power
    if (order.against_tolerance) order.theory = 1;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const StudyRow* row : series[key]) {
      if (!row->ok() || !(row->error_max_rel > floor)) continue;
      const double x = std::log(order.against_tolerance ? row->tol : row->dt);
      const double y = std::log(row->error_max_rel);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
      ++order.points;
    }
    const double n = order.points;
    const double denominator = n * sxx - sx * sx;
    order.slope = order.points >= 2 && denominator > 0.0 ? (n * sxy - sx * sy) / denominator
                                                          : std::nan("");
    out.push_back(order);
  }
  return out;
}

}  // namespace periflex
