#include "render/plot_axes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace periflex {

std::vector<double> nice_ticks(double lo, double hi, int most) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  most = std::max(2, most);
  // the smallest round step that keeps the count within `most`
  const double raw = (hi - lo) / (most - 1);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * decade >= raw * (1.0 - 1e-9)) {
      step = m * decade;
      break;
    }
  }
  // multiples of the step within the range, not accumulated sums (no 0.30000000000000004)
  const auto multiples = [&](double s) {
    std::vector<double> ticks;
    const double first = std::ceil(lo / s - 1e-9) * s;
    for (double t = first; t <= hi + 1e-9 * s && static_cast<int>(ticks.size()) < most + 1; t += s)
      ticks.push_back(std::round(t / s) * s);
    return ticks;
  };
  // a range straddling a multiple may hold only that one (-0.017 .. 0.017 at a step of 0.02):
  // the next smaller round step (5, 2, 1 times the decade, then the decade below) gives two
  std::vector<double> ticks = multiples(step);
  for (int k = 0; ticks.size() < 2 && k < 6; ++k) {
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    step *= mantissa > 4.0 ? 0.4 : 0.5;  // 10 -> 5 -> 2 -> 1 (5 -> 2: 0.4; 2 -> 1 and 10 -> 5: 0.5)
    ticks = multiples(step);
  }
  return ticks;
}

std::string tick_label(double value, double step) {
  step = std::fabs(step);
  if (std::fabs(value) < 1e-9 * step) value = 0.0;
  const double magnitude = std::max(std::fabs(value), step);
  const int step_decade = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  char text[48];
  if (magnitude >= 1e-3 && magnitude < 1e5) {
    // plain decimals, as many as the step has
    std::snprintf(text, sizeof text, "%.*f", std::max(0, -step_decade), value);
  } else {
    // very small or large: the significant digits the step needs
    const int digits = std::clamp(static_cast<int>(std::floor(std::log10(magnitude) + 1e-9)) - step_decade + 1, 1, 12);
    std::snprintf(text, sizeof text, "%.*g", digits, value);
  }
  return text;
}

bool visible_range(const std::vector<double>& x, const std::vector<double>& y, double x_lo, double x_hi,
                   double& y_lo, double& y_hi) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  const size_t n = std::min(x.size(), y.size());
  for (size_t i = 0; i < n; ++i) {
    if (x[i] < x_lo || x[i] > x_hi || !std::isfinite(y[i])) continue;
    lo = std::min(lo, y[i]);
    hi = std::max(hi, y[i]);
  }
  if (lo > hi) return false;
  // a margin, and some height for a flat line
  double pad = 0.05 * (hi - lo);
  if (pad <= 0.0) pad = lo != 0.0 ? 0.05 * std::fabs(lo) : 1.0;
  y_lo = lo - pad;
  y_hi = hi + pad;
  return true;
}

std::string plot_csv(const std::string& x_name, const std::string& y_name, const std::vector<double>& x,
                     const std::vector<double>& y, double x_lo, double x_hi) {
  return plot_csv(x_name, x, {y_name}, {&y}, x_lo, x_hi);
}

std::string plot_csv(const std::string& x_name, const std::vector<double>& x,
                     const std::vector<std::string>& y_names, const std::vector<const std::vector<double>*>& ys,
                     double x_lo, double x_hi) {
  std::string out = x_name;
  for (const std::string& name : y_names) out += "," + name;
  out += '\n';
  char buffer[32];
  // rows as long as the shortest column
  size_t n = x.size();
  for (const std::vector<double>* y : ys) n = std::min(n, y->size());
  for (size_t i = 0; i < n; ++i) {
    if (x[i] < x_lo || x[i] > x_hi) continue;
    out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, x[i]).ptr);
    for (const std::vector<double>* y : ys) {
      out += ',';
      out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, (*y)[i]).ptr);
    }
    out += '\n';
  }
  return out;
}

}  // namespace periflex
