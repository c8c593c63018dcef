// The rigid-body inspector's reactions are solved only while it asks for them: a model's snapshot
// carries them from the request on and none after it is withdrawn, and so do the snapshots the
// simulation thread publishes. (What they cost: bench/inspector_bench.cpp.)
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "app/sim_worker.h"

namespace periflex {
namespace {

using namespace std::chrono_literals;

const std::string kScenes = std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/";

TEST(ReactionsRequest, AModelSolvesThemOnlyWhileAsked) {
  const RunFactory factory = live_run_factory();
  for (const std::string name : {"slider_crank.toml", "four_bar.toml"}) {
    auto model = factory.build(factory.load(kScenes + name, {}));
    for (int k = 0; k < 200; ++k) model->step();
    Snapshot s;
    model->fill_snapshot(s);
    EXPECT_TRUE(s.reactions.empty()) << name;
    model->set_reactions(true);
    model->fill_snapshot(s);
    EXPECT_FALSE(s.reactions.empty()) << name;
    model->set_reactions(false);
    model->fill_snapshot(s);
    EXPECT_TRUE(s.reactions.empty()) << name << ": withdrawing the request does not stop the solves";
  }
}

// Waits (up to 20 s) until the worker has taken `step` steps.
bool wait_for_step(const SimWorker& worker, long step) {
  for (int k = 0; k < 4000; ++k) {
    if (worker.status().step == step) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

TEST(ReactionsRequest, TheSimulationThreadPublishesThemOnlyWhileAsked) {
  EventLog events(false);
  SimWorker worker(live_run_factory(), kScenes + "slider_crank.toml", {}, events);
  worker.start(false, 0.0);
  worker.send(SimCommand{command::Reactions{true}, "test"});
  worker.send(SimCommand{command::Step{3}, "test"});
  ASSERT_TRUE(wait_for_step(worker, 3));
  worker.update_snapshot();
  EXPECT_FALSE(worker.snapshot().reactions.empty());
  worker.send(SimCommand{command::Reactions{false}, "test"});
  worker.send(SimCommand{command::Step{1}, "test"});
  ASSERT_TRUE(wait_for_step(worker, 4));
  worker.update_snapshot();
  EXPECT_TRUE(worker.snapshot().reactions.empty());
  worker.stop();
}

}  // namespace
}  // namespace periflex
