// The command queue from the user interface to the simulation thread: requests arrive in
// the order each producer sent them, none are lost, and the consumer wakes when one comes.
#include "app/command_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace periflex {
namespace {

struct Tagged {
  int producer = 0;
  long sequence = 0;
};

TEST(CommandQueue, KeepsOrderOfEachProducerAndLosesNothing) {
  CommandQueue<Tagged> queue;
  constexpr int kProducers = 4;
  constexpr long kEach = 5000;
  std::vector<std::thread> producers;
  for (int p = 0; p < kProducers; ++p) {
    producers.emplace_back([&queue, p] {
      for (long i = 0; i < kEach; ++i) queue.push({p, i});
    });
  }

  // one consumer drains while the producers push, as the simulation thread does between steps
  std::vector<long> next(kProducers, 0);
  long received = 0, out_of_order = 0;
  while (received < kProducers * kEach) {
    for (const Tagged& t : queue.drain()) {
      if (t.sequence != next[t.producer]) ++out_of_order;
      next[t.producer] = t.sequence + 1;
      ++received;
    }
  }
  for (std::thread& t : producers) t.join();

  EXPECT_EQ(out_of_order, 0);
  EXPECT_EQ(received, kProducers * kEach);
  EXPECT_TRUE(queue.drain().empty());
  for (int p = 0; p < kProducers; ++p) EXPECT_EQ(next[p], kEach);
}

TEST(CommandQueue, DrainReturnsEverythingOldestFirst) {
  CommandQueue<int> queue;
  for (int i = 0; i < 5; ++i) queue.push(i);
  EXPECT_EQ(queue.size(), 5u);
  const std::vector<int> got = queue.drain();
  EXPECT_EQ(got, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(queue.size(), 0u);
}

TEST(CommandQueue, WaitForReturnsWhenARequestArrives) {
  CommandQueue<int> queue;
  // nothing pending: the wait times out
  EXPECT_FALSE(queue.wait_for(std::chrono::milliseconds(1)));
  std::thread producer([&queue] { queue.push(42); });
  // a generous timeout: the push wakes the wait long before it
  EXPECT_TRUE(queue.wait_for(std::chrono::seconds(10)));
  producer.join();
  EXPECT_EQ(queue.drain(), std::vector<int>{42});
}

}  // namespace
}  // namespace periflex
