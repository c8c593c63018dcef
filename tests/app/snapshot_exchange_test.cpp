// The snapshot exchange between the simulation and render threads: a reader never sees a
// torn or half-written value, values only move forward, and the newest one always arrives.
#include "app/snapshot_exchange.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace periflex {
namespace {

// Every field of a published value equals the same counter, so a torn read shows up
// as two fields that differ. The vector makes a copy take long enough to overlap.
struct CounterValue {
  long a = 0, b = 0, c = 0;
  std::vector<long> samples;
  void fill(long n) {
    a = b = c = n;
    samples.assign(2048, n);
  }
  bool consistent() const {
    if (a != b || b != c) return false;
    for (long s : samples) if (s != a) return false;
    return true;
  }
};

TEST(SnapshotExchange, ReaderNeverSeesTornValueAndValuesOnlyMoveForward) {
  SnapshotExchange<CounterValue> exchange;
  constexpr long kPublished = 20000;
  std::atomic<bool> done{false};

  std::thread writer([&] {
    for (long n = 1; n <= kPublished; ++n) {
      exchange.back().fill(n);
      exchange.publish();
    }
    done = true;
  });

  // read until the writer has finished and its last value has been taken
  long last = 0, updates = 0, torn = 0, backwards = 0;
  for (;;) {
    const bool finished = done.load();
    if (!exchange.update()) {
      if (finished) break;
      continue;
    }
    const CounterValue& v = exchange.front();
    ++updates;
    if (!v.consistent()) ++torn;
    if (v.a <= last) ++backwards;
    last = v.a;
  }
  writer.join();

  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_GT(updates, 0);
  // after the writer finished, the reader holds the very last value
  EXPECT_EQ(exchange.front().a, kPublished);
  EXPECT_TRUE(exchange.front().consistent());
}

TEST(SnapshotExchange, UpdateReportsOnlyNewValues) {
  SnapshotExchange<CounterValue> exchange;
  EXPECT_FALSE(exchange.has_front());
  EXPECT_FALSE(exchange.update());
  exchange.back().fill(7);
  exchange.publish();
  EXPECT_TRUE(exchange.update());
  EXPECT_TRUE(exchange.has_front());
  EXPECT_EQ(exchange.front().a, 7);
  // nothing new: the same value stays in front
  EXPECT_FALSE(exchange.update());
  EXPECT_EQ(exchange.front().a, 7);
  // two publications before a read: the reader skips straight to the newest
  exchange.back().fill(8);
  exchange.publish();
  exchange.back().fill(9);
  exchange.publish();
  EXPECT_TRUE(exchange.update());
  EXPECT_EQ(exchange.front().a, 9);
}

TEST(SnapshotExchange, WriterNeverWritesTheSlotTheReaderHolds) {
  SnapshotExchange<CounterValue> exchange;
  exchange.back().fill(1);
  exchange.publish();
  ASSERT_TRUE(exchange.update());
  const CounterValue* held = &exchange.front();
  // however often the writer publishes, its back slot is never the one the reader holds
  for (long n = 2; n < 50; ++n) {
    EXPECT_NE(&exchange.back(), held);
    exchange.back().fill(n);
    exchange.publish();
  }
  EXPECT_EQ(held->a, 1);
}

}  // namespace
}  // namespace periflex
