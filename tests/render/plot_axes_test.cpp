// The plots' axes: round ticks inside the range, labels without noise digits, the visible
// range of a zoomed series, and the exported text.
#include "render/plot_axes.h"

#include <gtest/gtest.h>

#include <tuple>

#include <cmath>

namespace periflex {
namespace {

TEST(PlotAxes, TicksAreRoundAndInsideTheRange) {
  const std::vector<double> t = nice_ticks(0.0, 1.0, 6);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_EQ(t.back(), 1.0);
  EXPECT_NEAR(t[3], 0.6, 1e-15);
  // an awkward range: a step of 1, 2 or 5 times a power of ten, at most 5 ticks
  const std::vector<double> u = nice_ticks(-0.0137, 0.0421, 5);
  ASSERT_GE(u.size(), 2u);
  ASSERT_LE(u.size(), 5u);
  const double step = u[1] - u[0];
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 || std::fabs(mantissa - 5) < 1e-9)
      << step;
  for (double v : u) {
    EXPECT_GE(v, -0.0137);
    EXPECT_LE(v, 0.0421);
    EXPECT_NEAR(std::remainder(v, step), 0.0, 1e-12);
  }
  EXPECT_EQ(nice_ticks(3.0, 3.0, 5), (std::vector<double>{3.0}));
}

// A range about zero whose round step would leave only the zero tick in it (the flexible
// pendulum's energies in a recorded frame's plot showed "0" alone): two ticks at least.
TEST(PlotAxes, RangeStraddlingOneMultipleStillGetsTwoTicks) {
  for (const auto& [lo, hi, most] : {std::tuple{-0.0175, 0.0175, 4}, std::tuple{-0.9, 0.9, 2},
                                     std::tuple{0.95, 1.05, 2}, std::tuple{-3.9e-6, 4.1e-6, 3}}) {
    const std::vector<double> t = nice_ticks(lo, hi, most);
    ASSERT_GE(t.size(), 2u) << lo << " .. " << hi;
    for (double v : t) {
      EXPECT_GE(v, lo) << lo << " .. " << hi;
      EXPECT_LE(v, hi) << lo << " .. " << hi;
    }
  }
}

TEST(PlotAxes, LabelsHaveTheStepsDigitsOnly) {
  EXPECT_EQ(tick_label(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(tick_label(-1e-18, 0.5), "0.0");  // not "-0.0"
  EXPECT_EQ(tick_label(1.25, 0.05), "1.25");
  EXPECT_EQ(tick_label(2e-6, 1e-6), "2e-06");
  EXPECT_EQ(tick_label(1200, 100), "1200");
  EXPECT_EQ(tick_label(400, 200), "400");
  EXPECT_EQ(tick_label(0.04, 0.02), "0.04");
  EXPECT_EQ(tick_label(3e6, 1e6), "3e+06");
}

TEST(PlotAxes, VisibleRangeFollowsTheZoom) {
  const std::vector<double> x = {0, 1, 2, 3, 4}, y = {5, -1, 2, 8, 100};
  double lo = 0, hi = 0;
  ASSERT_TRUE(visible_range(x, y, 0.5, 3.5, lo, hi));
  EXPECT_DOUBLE_EQ(lo, -1 - 0.45);
  EXPECT_DOUBLE_EQ(hi, 8 + 0.45);
  EXPECT_FALSE(visible_range(x, y, 10, 20, lo, hi));
  const std::vector<double> flat = {0, 0, 0, 0, 0};
  ASSERT_TRUE(visible_range(x, flat, 0, 4, lo, hi));
  EXPECT_LT(lo, 0);
  EXPECT_GT(hi, 0);
}

TEST(PlotAxes, CsvHoldsTheShownPointsExactly) {
  const std::vector<double> x = {0.1, 0.2, 0.30000000000000004}, y = {1.0 / 3.0, -2.5, 1e-300};
  EXPECT_EQ(plot_csv("t", "kinetic", x, y, 0.15, 1.0), "t,kinetic\n0.2,-2.5\n0.30000000000000004,1e-300\n");
}

TEST(PlotAxes, CsvOfSeveralSeriesHasOneColumnEach) {
  const std::vector<double> t = {0.0, 0.5, 1.0, 1.5}, work = {0.0, 2.0, 4.5, 7.0}, fracture = {0, 0, 0.25, 1e-9};
  EXPECT_EQ(plot_csv("t", t, {"driver_work", "fracture"}, {&work, &fracture}, 0.4, 1.2),
            "t,driver_work,fracture\n0.5,2,0\n1,4.5,0.25\n");
  // a column shorter than x (a series added later) ends the rows
  const std::vector<double> shorter = {5.0, 6.0};
  EXPECT_EQ(plot_csv("t", t, {"a", "b"}, {&work, &shorter}, 0.0, 9.0), "t,a,b\n0,0,5\n0.5,2,6\n");
}

}  // namespace
}  // namespace periflex
