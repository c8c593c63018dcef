// The window's history ring: states land on the first step at or after each mark (an interval
// that does not divide dt does not drift), the memory budget holds however long the run, the
// oldest half is thinned (the start kept, the recent past dense), large states come back bit
// for bit from their compressed form, and dropping the future puts the next mark right after
// the state kept.
#include "app/state_history.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace periflex {
namespace {

// A state of `n` coordinates whose values say which step it is (told apart after thinning).
SimState state_of(long step, long n) {
  SimState s;
  s.steps = step;
  s.q = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  s.qd = Eigen::VectorXd::Constant(n, 1e-3 * static_cast<double>(step));
  return s;
}

// Steps a clock of `dt` for `steps` steps, saving whatever is due, as the simulation thread does.
void run(StateHistory& h, double dt, long steps, long n = 8) {
  for (long k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) * dt;
    if (h.due(t)) h.add(state_of(k, n), t, k);
  }
}

TEST(StateHistory, SavesTheFirstStepAtOrAfterEachMarkWhenTheIntervalDoesNotDivideDt) {
  StateHistory h;
  const double dt = 1e-3, interval = 0.0333;   // 33.3 steps
  h.configure(interval, size_t{1} << 30, 0.0);
  h.add(state_of(0, 8), 0.0, 0);
  run(h, dt, 1000);
  // marks 0, 0.0333, ..., 0.9990 (30 of them after 0): one state each
  ASSERT_EQ(h.size(), 31u);
  for (size_t k = 0; k < h.size(); ++k) {
    const double mark = static_cast<double>(k) * interval;
    EXPECT_GE(h.time(k), mark - 1e-12) << "state " << k;
    EXPECT_LT(h.time(k) - dt, mark - 1e-12) << "state " << k << ": a step earlier was already past the mark";
  }
  // the mark at 1.0 - 0.001 (k = 30) is at step 999: the marks do not drift over the run
  EXPECT_EQ(h.step(30), 999);
}

TEST(StateHistory, OffSavesNothingAndIsNeverDue) {
  StateHistory h;
  h.configure(0.0, size_t{1} << 30, 0.0);
  for (long k = 0; k < 100000; ++k) ASSERT_FALSE(h.due(static_cast<double>(k) * 1e-3));
  EXPECT_EQ(h.size(), 0u);
  EXPECT_EQ(h.bytes(), 0u);
}

TEST(StateHistory, BudgetHoldsAndTheOldestHalfIsThinned) {
  StateHistory h;
  // states of about 16 kB, a budget of about 40 of them
  const long n = 1000;
  const size_t one = state_bytes(state_of(0, n));
  const size_t budget = 40 * one;
  // kept as they are, so the budget holds a known number of them
  h.compress_from(std::numeric_limits<size_t>::max());
  h.configure(1e-3, budget, 0.0);
  h.add(state_of(0, n), 0.0, 0);
  size_t most = 0;
  for (long k = 1; k <= 5000; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    if (!h.due(t)) continue;
    h.add(state_of(k, n), t, k);
    ASSERT_LE(h.bytes(), budget) << "after step " << k;
    most = std::max(most, h.size());
  }
  // full, not refusing: the newest state is the last step, the start is still there
  EXPECT_GE(h.size(), 20u);
  EXPECT_LE(most, 40u);
  EXPECT_EQ(h.step(h.size() - 1), 5000);
  EXPECT_EQ(h.step(0), 0);
  // the recent past at the full cadence, the far past thinned (gaps of 2, 4, ... intervals)
  EXPECT_EQ(h.step(h.size() - 1) - h.step(h.size() - 2), 1);
  EXPECT_GT(h.step(2) - h.step(1), 2);
  for (size_t i = 1; i < h.size(); ++i) EXPECT_LT(h.step(i - 1), h.step(i));
  // each entry still holds the state saved at its step
  SimState s;
  h.get(h.size() / 2, s);
  EXPECT_EQ(s.steps, h.step(h.size() / 2));

  // compressed (states over a 64th of the budget), the budget holds just the same
  StateHistory packed;
  packed.configure(1e-3, budget, 0.0);
  for (long k = 0; k <= 5000; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    if (!packed.due(t)) continue;
    packed.add(state_of(k, n), t, k);
    ASSERT_TRUE(packed.compressed());
    ASSERT_LE(packed.bytes(), budget) << "after step " << k;
  }
  EXPECT_GT(packed.size(), h.size());
  EXPECT_EQ(packed.step(0), 0);
  EXPECT_EQ(packed.step(packed.size() - 1), 5000);
}

TEST(StateHistory, AStateLargerThanTheBudgetIsNotKept) {
  StateHistory h;
  h.configure(1e-3, 1000, 0.0);
  h.add(state_of(0, 10000), 0.0, 0);
  EXPECT_EQ(h.size(), 0u);
  EXPECT_TRUE(h.too_large());
  EXPECT_EQ(h.bytes(), 0u);
}

TEST(StateHistory, LargeStatesAreCompressedAndComeBackBitForBit) {
  StateHistory h;
  // 64 MB: states over 1 MB are compressed
  h.configure(1e-3, size_t{64} << 20, 0.0);
  // a grid's coordinates and a smooth velocity field with noise in the low bits
  const long n = 200000;
  SimState big = state_of(7, n);
  for (long i = 0; i < n; ++i) big.qd[i] = std::sin(1e-3 * static_cast<double>(i)) * (1.0 + 1e-13 * static_cast<double>(i % 7));
  big.flex.resize(1);
  big.flex[0].broken_bits.assign(50000, 0);
  big.flex[0].broken_bits[123] = 0x10;
  const SimState copy = big;
  const size_t raw = state_bytes(big);
  ASSERT_GE(raw, h.budget() / kCompressBelowStates);
  h.add(std::move(big), 0.0, 0);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_TRUE(h.compressed());
  EXPECT_LT(h.bytes(), raw * 3 / 4) << "compression kept " << h.bytes() << " of " << raw << " bytes";
  SimState back;
  h.get(0, back);
  ASSERT_EQ(back.q.size(), copy.q.size());
  ASSERT_EQ(back.qd.size(), copy.qd.size());
  EXPECT_EQ(std::memcmp(back.q.data(), copy.q.data(), sizeof(double) * n), 0);
  EXPECT_EQ(std::memcmp(back.qd.data(), copy.qd.data(), sizeof(double) * n), 0);
  ASSERT_EQ(back.flex.size(), 1u);
  EXPECT_EQ(back.flex[0].broken_bits, copy.flex[0].broken_bits);
  EXPECT_EQ(back.steps, 7);
  // the same state under a budget that holds many of them is kept as it is
  StateHistory roomy;
  roomy.configure(1e-3, size_t{1} << 30, 0.0);
  SimState again = copy;
  roomy.add(std::move(again), 0.0, 0);
  EXPECT_FALSE(roomy.compressed());
  EXPECT_GE(roomy.bytes(), raw);
}

TEST(StateHistory, DroppingTheFutureSavesAgainAtTheMarksAfterTheStateKept) {
  StateHistory h;
  const double dt = 1e-3, interval = 0.0333;
  h.configure(interval, size_t{1} << 30, 0.0);
  h.add(state_of(0, 8), 0.0, 0);
  run(h, dt, 1000);
  std::vector<long> first;
  for (size_t i = 0; i < h.size(); ++i) first.push_back(h.step(i));
  // back to the state at index 10 (step 333), the run recomputed from there
  h.drop_after(10);
  ASSERT_EQ(h.size(), 11u);
  for (long k = h.step(10) + 1; k <= 1000; ++k) {
    const double t = static_cast<double>(k) * dt;
    if (h.due(t)) h.add(state_of(k, 8), t, k);
  }
  std::vector<long> again;
  for (size_t i = 0; i < h.size(); ++i) again.push_back(h.step(i));
  EXPECT_EQ(again, first);
  // nearest picks the closest time either side
  EXPECT_EQ(h.nearest(-1.0), 0u);
  EXPECT_EQ(h.nearest(0.0333 * 5 + 0.01), 5u);
  EXPECT_EQ(h.nearest(0.0333 * 5 + 0.02), 6u);
  EXPECT_EQ(h.nearest(7.0), h.size() - 1);
}

}  // namespace
}  // namespace periflex
