// The IFToMM A02 double four-bar run as a user runs it, compared with B0 of its own
// one-degree-of-freedom motion: the parallelogram's equation
//   3 theta'' + 3.5 g cos(theta) = 0,  B0 = (cos theta, sin theta)
// integrated by RK4 at 1e-5 s here, apart from the multibody code. Shared by the tests of
// singular positions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "run_output_files.h"
#include "run_program.h"

namespace periflex::testing {

constexpr double kFourBarGravity = 9.81;

// B0's x at multiples of `every` (keyed by the multiple), from (theta0, omega0) to `end`.
inline std::map<long, double> reference_b0_x(double theta0, double omega0, double end, double every) {
  auto f = [](double theta, double omega) {
    return std::pair{omega, -3.5 * kFourBarGravity * std::cos(theta) / 3.0};
  };
  const double h = 1e-5;
  const long steps = std::lround(end / h), stride = std::lround(every / h);
  std::map<long, double> out;
  double th = theta0, w = omega0;
  for (long i = 0; i <= steps; ++i) {
    if (i % stride == 0) out[i / stride] = std::cos(th);
    const auto k1 = f(th, w);
    const auto k2 = f(th + h / 2 * k1.first, w + h / 2 * k1.second);
    const auto k3 = f(th + h / 2 * k2.first, w + h / 2 * k2.second);
    const auto k4 = f(th + h * k3.first, w + h * k3.second);
    th += h / 6 * (k1.first + 2 * k2.first + 2 * k3.first + k4.first);
    w += h / 6 * (k1.second + 2 * k2.second + 2 * k3.second + k4.second);
  }
  return out;
}

// A number as the command line takes it back exactly.
inline std::string exact_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

struct FourBarOutcome {
  int exit_code = -1;
  std::string output;
  double max_error = 0.0, end_time = 0.0, max_pin_offset = 0.0;
  long compared = 0;
};

// Runs `scene_file` and compares probe.b0.x with the reference at the output instants.
inline FourBarOutcome run_and_compare(const std::string& tag, const std::string& scene_file,
                                      const std::string& arguments, const std::map<long, double>& reference,
                                      double every) {
  const auto out = fresh_directory("singular_" + tag);
  FourBarOutcome o;
  const auto r = run_periflex("run " + scene_file + " --quiet " + arguments + " --out " + out.string());
  o.exit_code = r.exit_code;
  o.output = r.output;
  const Series s = read_series(out / "series.csv");
  const int t = s.find_column("t"), x = s.find_column("probe.b0.x");
  const int px = s.find_column("probe.pin0_end.x"), py = s.find_column("probe.pin0_end.y");
  if (t < 0 || x < 0) return o;
  for (const auto& row : s.rows) {
    o.end_time = row[t];
    const double k = row[t] / every;
    if (px >= 0) o.max_pin_offset = std::max(o.max_pin_offset, std::hypot(row[px], row[py]));
    if (std::abs(k - std::round(k)) > 1e-6) continue;
    const auto found = reference.find(std::lround(k));
    if (found == reference.end()) continue;
    o.max_error = std::max(o.max_error, std::abs(row[x] - found->second));
    ++o.compared;
  }
  return o;
}

}  // namespace periflex::testing
