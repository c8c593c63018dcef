// scenes/concrete_beam_3pb.toml run as a user types it: the notched concrete beam of the
// bilinear-softening law gives a softening load-deflection curve, a peak and then a fall, while the
// energy its bonds take is booked as fracture energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli/child_run.h"
#include "../cli/run_output_files.h"

namespace periflex::testing {
namespace {

// The pin's imposed speed, from the scene's table: 0.04 m/s reached linearly over 1 ms.
double pin_speed(double t) { return 0.04 * std::min(t / 1e-3, 1.0); }

TEST(ConcreteBeam3pb, TheLoadPeaksAndThenFallsAsTheCrackGrows) {
  const auto out = std::filesystem::current_path() / "concrete_beam_3pb";
  std::filesystem::remove_all(out);
  const ChildResult r = run_child(
      {"run", std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/concrete_beam_3pb.toml", "--out", out.string(), "--quiet"},
      600.0);
  ASSERT_FALSE(r.timed_out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Series s = read_series(out / "series.csv");
  const int t = s.column("t"), work = s.column("driver_work"), pin = s.column("probe.pin.y"),
            fracture = s.column("fracture"), broken = s.column("broken_bonds");
  ASSERT_GE(std::min({t, work, pin, fracture, broken}), 0);
  // the load: the power the imposed motion takes over its speed (central differences), against the
  // pin's fall; rows of the first half millisecond, where the speed is small, are left out
  std::vector<double> load, deflection;
  for (size_t k = 1; k + 1 < s.rows.size(); ++k) {
    const double time = s.rows[k][t];
    if (time < 5e-4) continue;
    const double power = (s.rows[k + 1][work] - s.rows[k - 1][work]) / (s.rows[k + 1][t] - s.rows[k - 1][t]);
    load.push_back(power / pin_speed(time));
    deflection.push_back(s.rows.front()[pin] - s.rows[k][pin]);
  }
  ASSERT_GT(load.size(), 20u);
  const size_t peak = static_cast<size_t>(std::max_element(load.begin(), load.end()) - load.begin());
  // a peak inside the run, not at its end: the load rose to it and fell after it
  EXPECT_GT(peak, 3u);
  EXPECT_LT(peak + 10, load.size());
  EXPECT_GT(load[peak], 2.0 * load.front());
  // the fall: at the end the beam carries well under the peak (the crack has crossed most of the
  // ligament), and the deflection went on growing while the load fell
  EXPECT_LT(load.back(), 0.5 * load[peak]);
  EXPECT_GT(deflection.back(), 2.0 * deflection[peak]);
  // the softening bonds' energy is booked as fracture energy, and bonds broke
  EXPECT_GT(s.rows.back()[fracture], 0.0);
  EXPECT_GT(s.rows.back()[broken], 0.0);
}

}  // namespace
}  // namespace periflex::testing
