// The plots' history: one row per simulation step shown, every series.csv column the snapshot
// carries, bounded in size, and thinned so a long run keeps its start and its latest values.
#include "render/plot_history.h"

#include <gtest/gtest.h>

namespace periflex {
namespace {

Snapshot at_step(long step) {
  Snapshot s;
  s.step = step;
  s.time = 1e-3 * step;
  s.energies.kinetic = double(step);
  s.broken_bonds = step;
  return s;
}

TEST(PlotHistory, OnePointPerStepShown) {
  PlotHistory h(100);
  h.add(at_step(1), 10.0);
  h.add(at_step(1), 10.0);  // the same snapshot drawn twice
  h.add(at_step(2), 20.0);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h.values(h.index_of("kinetic")), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(h.values(h.index_of("steps_per_second")), (std::vector<double>{10.0, 20.0}));
  h.clear();
  EXPECT_EQ(h.size(), 0u);
  h.add(at_step(2), 0.0);  // after a reset the same step number counts again
  EXPECT_EQ(h.size(), 1u);
}

// A state from the window's history shown: the rows after it go, the state's own row comes next.
TEST(PlotHistory, GoingBackDropsTheRowsAfterTheStateShown) {
  PlotHistory h(100);
  for (long k = 1; k <= 10; ++k) h.add(at_step(k), 1.0);
  h.drop_from(at_step(4).time);
  EXPECT_EQ(h.values(h.index_of("kinetic")), (std::vector<double>{1.0, 2.0, 3.0}));
  h.add(at_step(4), 1.0);   // the state shown
  h.add(at_step(5), 1.0);   // and the run resumed from it
  EXPECT_EQ(h.values(h.index_of("kinetic")), (std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0}));
}

TEST(PlotHistory, KeepsEverySeriesColumnOfTheSnapshot) {
  PlotHistory h(100);
  auto columns = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"t", "kinetic", "probe.tip.x", "probe.tip.y"});
  for (long step = 0; step < 3; ++step) {
    Snapshot s = at_step(step);
    s.series_columns = columns;
    s.series = {s.time, 2.0 * step, 0.5 * step, -0.25 * step};
    h.add(s, 1.0);
  }
  ASSERT_EQ(h.columns(), (std::vector<std::string>{"t", "kinetic", "probe.tip.x", "probe.tip.y", "steps_per_second"}));
  EXPECT_EQ(h.values(h.index_of("probe.tip.y")), (std::vector<double>{0.0, -0.25, -0.5}));
  EXPECT_EQ(h.values(0), (std::vector<double>{0.0, 1e-3, 2e-3}));
  EXPECT_EQ(h.index_of("probe.none.x"), -1);
  // a scene with other columns starts a new history
  h.add(at_step(7), 1.0);
  EXPECT_EQ(h.size(), 1u);
  EXPECT_EQ(h.index_of("probe.tip.x"), -1);
}

TEST(PlotHistory, StaysBoundedAndKeepsFirstAndLatest) {
  PlotHistory h(64);
  for (long step = 0; step < 10000; ++step) h.add(at_step(step), 0.0);
  EXPECT_LE(h.size(), 64u);
  EXPECT_GE(h.size(), 32u);
  const std::vector<double>& k = h.values(h.index_of("kinetic"));
  EXPECT_EQ(k.front(), 0.0);
  EXPECT_EQ(k.back(), 9999.0);
  // still in time order
  for (size_t i = 1; i < k.size(); ++i) EXPECT_LT(k[i - 1], k[i]);
  EXPECT_DOUBLE_EQ(h.first_time(), 0.0);
  EXPECT_DOUBLE_EQ(h.last_time(), 9.999);
  // every series is thinned alike
  EXPECT_EQ(h.values(h.index_of("broken_bonds")), k);
}

}  // namespace
}  // namespace periflex
