// The record of the energy balance a passage through a singular position is judged against.
#include "solve/balance_drift.h"

#include <gtest/gtest.h>

#include <cmath>

namespace periflex {
namespace {

// Nothing to go on before two samples: no drift.
TEST(BalanceDrift, FewerThanTwoSamplesShowNoChange) {
  BalanceDrift drift;
  EXPECT_EQ(drift.change_over(1.0), 0.0);
  drift.record(0.0, 5.0);
  EXPECT_EQ(drift.change_over(1.0), 0.0);
}

// A balance falling at 2 J/s moves by 2 J/s times the span asked, whether the samples reach
// that far back or not (then at their mean rate).
TEST(BalanceDrift, SteadyDriftScalesWithTheSpan) {
  BalanceDrift drift;
  for (int k = 0; k <= 10; ++k) drift.record(0.01 * k, -2.0 * 0.01 * k);
  EXPECT_NEAR(drift.change_over(0.05), 0.1, 1e-12);
  EXPECT_NEAR(drift.change_over(0.5), 1.0, 1e-12);
}

// The change is measured over the most recent stretch: an error that grew fast long ago and is
// still now counts as still.
TEST(BalanceDrift, OnlyTheRecentStretchCounts) {
  BalanceDrift drift;
  for (int k = 0; k < 10; ++k) drift.record(0.01 * k, 3.0 * k);
  for (int k = 10; k < 20; ++k) drift.record(0.01 * k, 27.0);
  EXPECT_NEAR(drift.change_over(0.05), 0.0, 1e-12);
}

// An error that swings step by step counts by the net change over the span, not by the sum of
// its swings; the ring keeps only the last kSamples samples (older ones are overwritten). Times
// are multiples of 1/1024 s so that the spans compare exactly.
TEST(BalanceDrift, SwingsCountByTheirNetChangeAndTheRingWraps) {
  BalanceDrift drift;
  const double h = 1.0 / 1024.0;
  const auto balance = [](int k) { return (k % 2 == 0 ? 1e-3 : -1e-3) + 1e-4 * k; };
  const int n = 3 * BalanceDrift::kSamples + 5;
  for (int k = 0; k < n; ++k) drift.record(h * k, balance(k));
  EXPECT_EQ(drift.size(), BalanceDrift::kSamples);
  // 10 steps back (same parity): the swing cancels, the net change is 10 x 1e-4 J
  EXPECT_NEAR(drift.change_over(10 * h), 1e-3, 1e-12);
  // beyond the ring: the change between the oldest and newest samples kept, at that rate
  const int newest = n - 1, oldest = n - BalanceDrift::kSamples;
  const double expected = std::abs(balance(newest) - balance(oldest)) / (h * (newest - oldest));
  EXPECT_NEAR(drift.change_over(1.0), expected, 1e-9);
  drift.clear();
  EXPECT_EQ(drift.change_over(1.0), 0.0);
}

}  // namespace
}  // namespace periflex
