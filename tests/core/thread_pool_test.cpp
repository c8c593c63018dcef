// The solver's team of threads (core/thread_pool.h): every item runs once, on more than one thread
// when the team has more; nested and concurrent loops run inline instead of waiting on each other;
// an exception reaches the caller; the team follows OpenMP's thread setting.
#include "core/thread_pool.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace periflex {
namespace {

// Sets the team size for the scope of a test and puts the previous one back.
class TeamSize {
 public:
  explicit TeamSize(int threads) : saved_(omp_get_max_threads()) { omp_set_num_threads(threads); }
  ~TeamSize() { omp_set_num_threads(saved_); }
  TeamSize(const TeamSize&) = delete;
  TeamSize& operator=(const TeamSize&) = delete;

 private:
  int saved_;
};

// The threads a loop of `items` items runs on when every item holds its thread until all of them
// started (or 2 s passed): a full team runs them all at once, one thread each.
int threads_running(int items) {
  std::mutex lock;
  std::set<std::thread::id> seen;
  std::atomic<int> started{0};
  parallel_for(items, [&](int64_t) {
    {
      std::lock_guard<std::mutex> guard(lock);
      seen.insert(std::this_thread::get_id());
    }
    started.fetch_add(1);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (started.load() < items && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
  });
  return static_cast<int>(seen.size());
}

TEST(ThreadPool, EveryItemRunsExactlyOnce) {
  TeamSize team(4);
  for (int64_t count : {0, 1, 2, 3, 17, 1000, 100000}) {
    std::vector<std::atomic<int>> runs(static_cast<size_t>(count));
    parallel_for(count, [&](int64_t item) { runs[static_cast<size_t>(item)].fetch_add(1); });
    for (int64_t item = 0; item < count; ++item) ASSERT_EQ(runs[static_cast<size_t>(item)].load(), 1) << item << " of " << count;
  }
}

TEST(ThreadPool, ItemsRunOnTwoThreadsAtOnce) {
  TeamSize team(2);
  // each item waits for the other to start: only two threads running at once finish both quickly
  std::atomic<int> started{0};
  std::mutex lock;
  std::set<std::thread::id> threads;
  const auto begin = std::chrono::steady_clock::now();
  parallel_for(2, [&](int64_t) {
    {
      std::lock_guard<std::mutex> guard(lock);
      threads.insert(std::this_thread::get_id());
    }
    started.fetch_add(1);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
  });
  EXPECT_EQ(threads.size(), 2u);
  EXPECT_LT(std::chrono::steady_clock::now() - begin, std::chrono::seconds(10));
  EXPECT_GT(team_worker_cpu_seconds(), 0.0);
}

TEST(ThreadPool, OneThreadRunsTheItemsInOrderOnTheCaller) {
  TeamSize team(1);
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<int64_t> order;
  parallel_for(50, [&](int64_t item) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(item);
  });
  ASSERT_EQ(order.size(), 50u);
  for (int64_t k = 0; k < 50; ++k) EXPECT_EQ(order[static_cast<size_t>(k)], k);
}

TEST(ThreadPool, ALoopInsideALoopRunsOnItsOwnThread) {
  TeamSize team(3);
  std::atomic<int> foreign{0}, inner_runs{0};
  parallel_for(40, [&](int64_t) {
    const std::thread::id outer = std::this_thread::get_id();
    parallel_for(25, [&](int64_t) {
      inner_runs.fetch_add(1);
      if (std::this_thread::get_id() != outer) foreign.fetch_add(1);
    });
  });
  EXPECT_EQ(inner_runs.load(), 40 * 25);
  EXPECT_EQ(foreign.load(), 0);
}

TEST(ThreadPool, LoopsFromTwoThreadsAtOnceBothComplete) {
  // two simulations stepped on two threads of the program (the window's worker and a script)
  std::atomic<int64_t> sums[2] = {0, 0};
  auto run = [&](int which) {
    TeamSize team(2);
    for (int repeat = 0; repeat < 200; ++repeat)
      parallel_for(100, [&](int64_t item) { sums[which].fetch_add(item + 1); });
  };
  std::thread first(run, 0), second(run, 1);
  first.join();
  second.join();
  EXPECT_EQ(sums[0].load(), 200 * 5050);
  EXPECT_EQ(sums[1].load(), 200 * 5050);
}

TEST(ThreadPool, AnItemsExceptionReachesTheCallerAndTheTeamGoesOn) {
  TeamSize team(2);
  std::atomic<int> runs{0};
  EXPECT_THROW(parallel_for(1000,
                            [&](int64_t item) {
                              runs.fetch_add(1);
                              if (item == 500) throw std::runtime_error("item 500");
                            }),
               std::runtime_error);
  EXPECT_LE(runs.load(), 1000);
  std::atomic<int> after{0};
  parallel_for(1000, [&](int64_t) { after.fetch_add(1); });
  EXPECT_EQ(after.load(), 1000);
}

TEST(ThreadPool, TheTeamGrowsAndShrinksWithTheSetting) {
  for (int threads : {4, 1, 3, 2}) {
    TeamSize team(threads);
    EXPECT_EQ(threads_running(threads), threads) << threads << " threads asked for";
  }
}

// A scope sets the calling thread's team for its life, nests, and gives the setting back; OpenMP's
// own setting is never touched, and another thread's team is not this one's.
TEST(ThreadPool, ATeamSizeScopeHoldsForItsLifeOnItsThreadAlone) {
  TeamSize omp(4);
  EXPECT_EQ(team_size(), 4);
  {
    const TeamSizeScope three(3);
    EXPECT_EQ(team_size(), 3);
    {
      const TeamSizeScope unchanged(0);
      EXPECT_EQ(team_size(), 3);
      const TeamSizeScope two(2);
      EXPECT_EQ(team_size(), 2);
      // the loop runs on the scope's team: two threads, though OpenMP's setting says four
      EXPECT_EQ(threads_running(3), 2);
    }
    EXPECT_EQ(team_size(), 3);
    int other = 0;
    std::thread([&] { other = team_size(); }).join();
    EXPECT_NE(other, 3);
    EXPECT_EQ(omp_get_max_threads(), 4);
  }
  EXPECT_EQ(team_size(), 4);
}

}  // namespace
}  // namespace periflex
