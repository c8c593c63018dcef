// Attachments that share particles, run as a user runs them: the notched plate held whole by
// both grips (every particle attached to two bodies, 16 003 equations of which 7 997 depend on
// the others). The redundancy analysis must take about linear time (it once took hours), and
// the plate, welded to both grips, must turn as one rigid body about the left pin.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "run_output_files.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

TEST(SharedParticles, PlateHeldWholeByBothGripsTurnsAsOneRigidBody) {
  const auto out = fresh_directory("plate_held_whole");
  const auto start = std::chrono::steady_clock::now();
  // 300 us: 750 steps, output rows every 10 us
  const auto r = run_periflex("run " + std::string(PERIFLEX_TEST_DATA) +
                              "/scenes/plate_held_whole.toml --quiet --until 3e-4 --out " + out.string());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // set-up and run in seconds (a few on a loaded two-core machine; the analysis was n^2.5)
  EXPECT_LT(seconds, 30.0);
  const Series t = read_series(out / "series.csv");
  ASSERT_GE(t.rows.size(), 30u);
  EXPECT_NEAR(t.rows.back()[t.column("t")], 3e-4, 1e-12);

  // every point of the plate and of both grips turns about the left pin by the driven angle
  const double pin_x = -0.0485, pin_y = 0.02;
  const int angle = t.column("probe.left_grip_corner.angle");
  const int right_angle = t.column("probe.right_grip_corner.angle");
  ASSERT_GE(angle, 0);
  ASSERT_GE(right_angle, 0);
  double worst = 0.0, worst_angle = 0.0;
  for (const std::string probe : {"notch_tip", "right_grip_corner", "left_grip_corner"}) {
    const int x = t.column("probe." + probe + ".x"), y = t.column("probe." + probe + ".y");
    ASSERT_GE(x, 0) << probe;
    const double x0 = t.rows.front()[x] - pin_x, y0 = t.rows.front()[y] - pin_y;
    for (const auto& row : t.rows) {
      const double a = row[angle], c = std::cos(a), s = std::sin(a);
      worst = std::max(worst, std::hypot(row[x] - (pin_x + c * x0 - s * y0), row[y] - (pin_y + s * x0 + c * y0)));
    }
  }
  for (const auto& row : t.rows) worst_angle = std::max(worst_angle, std::abs(row[right_angle] - row[angle]));
  EXPECT_LT(worst, 1e-7) << "m from the rigid motion";
  EXPECT_LT(worst_angle, 1e-9);
  // and it did turn: -6 rad/s for 300 us
  EXPECT_NEAR(t.rows.back()[angle], -6.0 * 3e-4, 1e-9);
  // the elastic energy stays at round-off: no bond is stretched
  const int elastic = t.column("potential_elastic");
  for (const auto& row : t.rows) EXPECT_LT(row[elastic], 1e-9);
}

}  // namespace
}  // namespace periflex::testing
