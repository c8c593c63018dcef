// The run's clock and the shared "have we reached t?" answer.
#include "core/sim_time.h"

#include <gtest/gtest.h>

namespace periflex {
namespace {

// Ten million steps of 1e-4 s: the clock multiplies, so it is within one rounding of n * dt,
// where a running sum is off by about 1e-9 s (thousands of units in the last place).
TEST(SimClock, TimeAfterManyStepsIsOneRoundingFromStepsTimesDt) {
  SimClock clock;
  const double dt = 1e-4;
  clock.reset(0.0, dt);
  double sum = 0.0;
  const long n = 10'000'000;
  for (long k = 0; k < n; ++k) {
    clock.tick();
    sum += dt;
  }
  const double exact = static_cast<double>(n) * dt;
  EXPECT_EQ(clock.time(), exact);
  // the running sum it replaces drifts: this is why rows used to fall a step late
  EXPECT_GT(std::abs(sum - exact), 1e-10);
}

TEST(SimClock, LandingMovesTheOriginAndSetDtKeepsTheTime) {
  SimClock clock;
  clock.reset(0.0, 3e-3);
  for (int k = 0; k < 166; ++k) clock.tick();
  clock.land(0.5);
  EXPECT_EQ(clock.time(), 0.5);
  clock.tick();
  EXPECT_EQ(clock.time(), 0.5 + 3e-3);
  const double before = clock.time();
  clock.set_dt(1e-3);
  EXPECT_EQ(clock.time(), before);
  EXPECT_EQ(clock.next_time(), before + 1e-3);
}

// One tolerance for every question: a billionth of a step near 0, a few dozen units in the last
// place far from it (where a billionth of a step is below round-off).
TEST(TimeReached, ToleranceCoversRoundOffAtLargeTimes) {
  EXPECT_TRUE(time_reached(1.0, 1.0, 1e-3));
  EXPECT_TRUE(time_reached(1.0 - 1e-13, 1.0, 1e-3));
  EXPECT_FALSE(time_reached(1.0 - 1e-11, 1.0, 1e-3));
  // t / dt = 1e9: one unit in the last place of t is far more than 1e-9 dt
  const double t = 1e3, dt = 1e-6;
  EXPECT_TRUE(time_reached(std::nextafter(t, 0.0), t, dt));
  EXPECT_FALSE(time_reached(t - 0.5 * dt, t, dt));
}

}  // namespace
}  // namespace periflex
