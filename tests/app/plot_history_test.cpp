// The plots' history: one point per simulation step shown, bounded in size, and thinned so a
// long run keeps its start and its latest values.
#include "app/plot_history.h"

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
  EXPECT_EQ(h.values(PlotHistory::kKinetic), (std::vector<float>{1.0f, 2.0f}));
  EXPECT_EQ(h.values(PlotHistory::kStepsPerSecond), (std::vector<float>{10.0f, 20.0f}));
  h.clear();
  EXPECT_EQ(h.size(), 0u);
  h.add(at_step(2), 0.0);  // after a reset the same step number counts again
  EXPECT_EQ(h.size(), 1u);
}

TEST(PlotHistory, StaysBoundedAndKeepsFirstAndLatest) {
  PlotHistory h(64);
  for (long step = 0; step < 10000; ++step) h.add(at_step(step), 0.0);
  EXPECT_LE(h.size(), 64u);
  EXPECT_GE(h.size(), 32u);
  const std::vector<float>& k = h.values(PlotHistory::kKinetic);
  EXPECT_EQ(k.front(), 0.0f);
  EXPECT_EQ(k.back(), 9999.0f);
  // still in time order
  for (size_t i = 1; i < k.size(); ++i) EXPECT_LT(k[i - 1], k[i]);
  EXPECT_DOUBLE_EQ(h.first_time(), 0.0);
  EXPECT_DOUBLE_EQ(h.last_time(), 9.999);
  // every series is thinned alike
  EXPECT_EQ(h.values(PlotHistory::kBrokenBonds), k);
}

}  // namespace
}  // namespace periflex
