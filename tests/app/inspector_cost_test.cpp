// What the rigid-body inspector costs the simulation thread: while it is open every snapshot
// carries the joints' reactions, one more solve of the equations of motion; while it is closed
// none is made. Measured on the slider-crank and the four-bar: the snapshot alone, and the
// steps per second of the worker running flat out (snapshots up to 120 times a second).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "app/sim_worker.h"

namespace periflex {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

const std::string kScenes = std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/";

// seconds of one fill_snapshot of `model`: the mean over `count`, the best of five such batches
// (the machine is shared: the best batch is the one least disturbed)
double snapshot_seconds(const SteppedModel& model, Snapshot& s, int count) {
  double best = 1e30;
  for (int batch = 0; batch < 5; ++batch) {
    const auto start = Clock::now();
    for (int k = 0; k < count; ++k) model.fill_snapshot(s);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count() / count);
  }
  return best;
}

// steps per second of a worker running as fast as it can for about a second, reactions asked or not
double worker_steps_per_second(const std::string& scene, bool reactions) {
  EventLog events(false);
  SimWorker worker(simulation_model_factory(), scene, {"solver.end_time=1000"}, events);
  SimCommand ask{command::Reactions{reactions}, "test"};
  worker.send(ask);
  worker.start(true, 0.0);
  // the rate is measured over half-second windows: read it after two of them
  std::this_thread::sleep_for(1200ms);
  const WorkerStatus s = worker.status();
  worker.stop();
  return s.steps_per_second;
}

TEST(InspectorCost, ReactionsAreSolvedOnlyWhileAskedAndTheirCostIsMeasured) {
  const ModelFactory factory = simulation_model_factory();
  for (const std::string name : {"slider_crank.toml", "four_bar.toml"}) {
    auto model = factory.build(factory.load(kScenes + name, {}));
    for (int k = 0; k < 200; ++k) model->step();
    Snapshot s;
    // closed: no reactions in the snapshot, so no solve was made for them
    model->fill_snapshot(s);
    EXPECT_TRUE(s.reactions.empty()) << name;
    const double closed = snapshot_seconds(*model, s, 400);
    // open: every joint's and driver's reaction
    model->set_reactions(true);
    model->fill_snapshot(s);
    EXPECT_FALSE(s.reactions.empty()) << name;
    const double open = snapshot_seconds(*model, s, 400);
    model->set_reactions(false);
    model->fill_snapshot(s);
    EXPECT_TRUE(s.reactions.empty()) << name << ": closing the inspector does not stop the solves";
    // one step, for scale (the best of five batches too)
    double step = 1e30;
    for (int batch = 0; batch < 5; ++batch) {
      const auto start = Clock::now();
      for (int k = 0; k < 400; ++k) model->step();
      step = std::min(step, std::chrono::duration<double>(Clock::now() - start).count() / 400);
    }
    const double without = worker_steps_per_second(kScenes + name, false);
    const double with = worker_steps_per_second(kScenes + name, true);
    std::printf("%s: snapshot %.2f us closed, %.2f us open (+%.2f us, %.2f steps' worth); step %.2f us; "
                "worker %.0f steps/s closed, %.0f open\n",
                name.c_str(), 1e6 * closed, 1e6 * open, 1e6 * (open - closed), (open - closed) / step, 1e6 * step,
                without, with);
    EXPECT_GT(without, 0.0) << name;
    EXPECT_GT(with, 0.0) << name;
  }
}

}  // namespace
}  // namespace periflex
