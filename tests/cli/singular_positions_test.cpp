// The IFToMM A02 double four-bar through its singular positions, run as a user runs it: at
// every step size either the physical branch (B0 within 1e-3 m of the one-degree-of-freedom
// reference) with exit 0, or exit 3 with a diagnostic naming the position; never a wrong
// branch with exit 0. The reference integrates the parallelogram's own equation
//   3 theta'' + 3.5 g cos(theta) = 0,  B0 = (cos theta, sin theta)
// by RK4 at 1e-5 s here, apart from the multibody code.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "core/vec2.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

constexpr double kGravity = 9.81;

// B0's x at multiples of `every` (keyed by the multiple), from (theta0, omega0) to `end`.
std::map<long, double> reference_b0_x(double theta0, double omega0, double end, double every) {
  auto f = [](double theta, double omega) { return std::pair{omega, -3.5 * kGravity * std::cos(theta) / 3.0}; };
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

struct Series {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    for (size_t k = 0; k < names.size(); ++k)
      if (names[k] == name) return static_cast<int>(k);
    return -1;
  }
};

Series read_series(const std::filesystem::path& file) {
  Series s;
  std::istringstream text(read_text(file));
  std::string line;
  std::getline(text, line);
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) s.names.push_back(cell);
  while (std::getline(text, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    for (std::string cell; std::getline(row, cell, ',');) values.push_back(std::stod(cell));
    s.rows.push_back(values);
  }
  return s;
}

std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

struct Outcome {
  int exit_code = -1;
  std::string output;
  double max_error = 0.0, end_time = 0.0, max_pin_offset = 0.0;
  long compared = 0;
};

// Runs `scene` and compares probe.b0.x with the reference at the output instants.
Outcome run_and_compare(const std::string& tag, const std::string& scene_file, const std::string& arguments,
                        const std::map<long, double>& reference, double every) {
  const auto out = fresh_directory("singular_" + tag);
  Outcome o;
  const auto r = run_periflex("run " + scene_file + " --quiet " + arguments + " --out " + out.string());
  o.exit_code = r.exit_code;
  o.output = r.output;
  const Series s = read_series(out / "series.csv");
  const int t = s.column("t"), x = s.column("probe.b0.x");
  const int px = s.column("probe.pin0_end.x"), py = s.column("probe.pin0_end.y");
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

// Exit 0 on the physical branch, or exit 3 naming the singular position; nothing else.
void expect_branch_or_diagnostic(const Outcome& o, double end, const std::string& what) {
  if (o.exit_code == 3) {
    EXPECT_NE(o.output.find("singular"), std::string::npos) << what << ": " << o.output;
    return;
  }
  ASSERT_EQ(o.exit_code, 0) << what << ": " << o.output;
  EXPECT_NEAR(o.end_time, end, 1e-9) << what;
  EXPECT_GE(o.compared, 4) << what;
  EXPECT_LT(o.max_error, 1e-3) << what << " ran onto a wrong branch with exit 0";
}

const std::vector<double> kStepSizes = {2.5e-2, 1e-2, 5e-3, 2.5e-3, 1e-3, 5e-4, 2.5e-4,
                                        1e-4,   5e-5, 2.5e-5, 1.25e-5};

// Every step size passes the first dead point of the benchmark's own motion. Small steps over
// the whole 10 s would take minutes, so this starts 0.2 rad before a dead point at the
// benchmark's energy (tests/data/scenes/a02_near_dead_point.toml) and runs 0.1 s past it.
void sweep_dead_point(const std::string& integrator) {
  const double theta0 = 0.2, omega0 = -std::sqrt((1.5 + 3.5 * kGravity * (1.0 - std::sin(theta0))) / 1.5);
  const double every = 0.005, end = 0.1;
  const auto reference = reference_b0_x(theta0, omega0, end, every);
  const std::string file = std::string(PERIFLEX_TEST_DATA) + "/scenes/a02_near_dead_point.toml";
  for (double dt : kStepSizes) {
    const std::string what = integrator + " dt " + text(dt);
    const auto o = run_and_compare("sweep_" + integrator, file, "--integrator " + integrator + " --dt " + text(dt), reference, every);
    expect_branch_or_diagnostic(o, end, what);
  }
}

TEST(SingularPositions, DoubleFourBarPassesTheDeadPointAtEveryStepSizeRk4) { sweep_dead_point("rk4"); }
TEST(SingularPositions, DoubleFourBarPassesTheDeadPointAtEveryStepSizeDopri54) { sweep_dead_point("dopri54"); }

// The benchmark scene as shipped, over its whole 10 s (20 dead points), at the step sizes that
// fit in a few seconds.
TEST(SingularPositions, BenchmarkA02OverTenSeconds) {
  const double every = 0.01, end = 10.0;
  const auto reference = reference_b0_x(kPi / 2, -1.0, end, every);
  for (const std::string integrator : {"rk4", "dopri54"}) {
    for (double dt : {2.5e-2, 1e-2, 2.5e-3, 1e-3}) {
      const std::string what = integrator + " dt " + text(dt);
      const auto o = run_and_compare("a02", scene("benchmarks/a02_double_four_bar.toml"),
                                     "--integrator " + integrator + " --dt " + text(dt), reference, every);
      expect_branch_or_diagnostic(o, end, what);
    }
  }
}

// Started in the singular position (two rows dependent at t = 0): the rows come back as soon
// as the motion leaves it, so the crank stays on its pin and the motion follows the reference
// back and forth through the dead points.
TEST(SingularPositions, SingularStartKeepsTheCrankOnItsPin) {
  const double every = 0.005, end = 3.0;
  const auto reference = reference_b0_x(0.0, 1.0, end, every);
  const auto o = run_and_compare("start", std::string(PERIFLEX_TEST_DATA) + "/scenes/a02_singular_start.toml", "", reference,
                                 every);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_LT(o.max_pin_offset, 1e-6);
  EXPECT_LT(o.max_error, 1e-3);
  EXPECT_GT(o.compared, 500);
}


// The same start with the second coupler flexible (a virtual body holding a peridynamic
// strip): a large system, whose dependent rows were once fixed at t = 0 for the whole run. Its
// rows must come back as the rank does, so every joint stays closed, measured from the probes'
// positions (not from the solver's own violation figure), through the dead points it passes.
TEST(SingularPositions, FlexibleCouplerSingularStartKeepsEveryJointClosed) {
  const auto out = fresh_directory("singular_flexible");
  const auto r = run_periflex("run " + std::string(PERIFLEX_TEST_DATA) +
                              "/scenes/a02_singular_start_flexible.toml --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Series s = read_series(out / "series.csv");
  ASSERT_GT(s.rows.size(), 500u);
  EXPECT_NEAR(s.rows.back()[s.column("t")], 3.0, 1e-9);
  // a probe's distance from a fixed point, or from another probe, over the run
  auto largest_gap = [&](const std::string& a, double x, double y, const std::string& b) {
    const int ax = s.column("probe." + a + ".x"), ay = s.column("probe." + a + ".y");
    const int bx = b.empty() ? -1 : s.column("probe." + b + ".x"), by = b.empty() ? -1 : s.column("probe." + b + ".y");
    EXPECT_GE(ax, 0) << a;
    double gap = 0.0;
    for (const auto& row : s.rows) {
      const double px = bx >= 0 ? row[bx] : x, py = by >= 0 ? row[by] : y;
      gap = std::max(gap, std::hypot(row[ax] - px, row[ay] - py));
    }
    return gap;
  };
  EXPECT_LT(largest_gap("pin0_end", 0.0, 0.0, ""), 1e-6);
  EXPECT_LT(largest_gap("pin1_end", 1.0, 0.0, ""), 1e-6);
  EXPECT_LT(largest_gap("pin2_end", 2.0, 0.0, ""), 1e-6);
  EXPECT_LT(largest_gap("b1", 0.0, 0.0, "coupler2_start"), 1e-6);
  EXPECT_LT(largest_gap("b2", 0.0, 0.0, "coupler2_end"), 1e-6);
  // and the mechanism did swing through the dead points: B0 went below the ground line
  const int b0y = s.column("probe.b0.y");
  double lowest = 0.0;
  for (const auto& row : s.rows) lowest = std::min(lowest, row[b0y]);
  EXPECT_LT(lowest, -0.5);
}

}  // namespace
}  // namespace periflex::testing
