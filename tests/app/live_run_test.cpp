// The window's scene loader: a scene picked or reloaded in the window passes the same checks as
// one given on the command line, so a scene over its limits is refused before anything is built.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "app/sim_worker.h"
#include "core/error.h"

namespace periflex {
namespace {

using namespace std::chrono_literals;

const std::string kData = PERIFLEX_TEST_DATA;

TEST(LiveRun, LoaderRefusesASceneOverItsLimits) {
  const RunFactory factory = live_run_factory();
  try {
    factory.load(kData + "/scenes/app/plate_over_particle_limit.toml", {});
    FAIL() << "a scene of 400 particles with max_particles = 50 was loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_particles"), std::string::npos) << e.what();
  }
}

TEST(LiveRun, SwitchingToASceneOverItsLimitsKeepsTheCurrentOne) {
  EventLog events(false);
  const std::string start = kData + "/scenes/run/falling_body.toml";
  SimWorker worker(live_run_factory(), start, {}, events);
  worker.start(false, 1.0);
  SimCommand load{command::LoadScene{kData + "/scenes/app/plate_over_particle_limit.toml"}, "test"};
  worker.send(load);
  WorkerStatus s = worker.status();
  for (int k = 0; k < 500 && s.commands_applied < 1; ++k) {
    std::this_thread::sleep_for(10ms);
    s = worker.status();
  }
  worker.stop();
  ASSERT_GE(s.commands_applied, 1);
  EXPECT_EQ(s.scene_path, start);
  EXPECT_NE(s.load_error.find("max_particles"), std::string::npos) << s.load_error;
}

// Reset in the window puts back the state the model started in (the model is not built again):
// a cracked plate reset and run again repeats its first run bit for bit, cracks included.
TEST(LiveRun, ResetRestoresTheStartAndRepeatsTheRun) {
  const RunFactory factory = live_run_factory();
  SceneDef scene = factory.load(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml", {});
  // one solver thread: the ThreadSanitizer build runs this label, and OpenMP's own threads
  // (libgomp is not instrumented) would show as races that are not the program's
  scene.solver.threads = 1;
  std::unique_ptr<SteppedRun> model = factory.build(scene);
  const long steps = 1750;  // the crack runs from about step 1600
  Snapshot first, again, fresh;
  for (long k = 0; k < steps; ++k) model->step();
  model->fill_snapshot(first);
  ASSERT_GT(first.broken_bonds, 0);
  ASSERT_TRUE(model->reset_to_start());
  EXPECT_EQ(model->time(), 0.0);
  EXPECT_EQ(model->step_count(), 0);
  Snapshot start;
  model->fill_snapshot(start);
  EXPECT_EQ(start.broken_bonds, 0);
  for (long k = 0; k < steps; ++k) model->step();
  model->fill_snapshot(again);
  std::unique_ptr<SteppedRun> built = factory.build(scene);
  for (long k = 0; k < steps; ++k) built->step();
  built->fill_snapshot(fresh);
  for (const Snapshot* other : {&again, &fresh}) {
    EXPECT_EQ(other->time, first.time);
    EXPECT_EQ(other->broken_bonds, first.broken_bonds);
    EXPECT_EQ(other->px, first.px);
    EXPECT_EQ(other->py, first.py);
    EXPECT_EQ(other->damage, first.damage);
    EXPECT_EQ(other->vx, first.vx);
  }
}

// Scrubbing back in the window's history and resuming repeats the original run bit for bit: the
// notched plate cracked, taken back to a state before the crack (kept at a cadence that does not
// divide dt), resumed and stepped to the same instant, has the same particles, damage and series
// row as the first time.
TEST(LiveRun, ScrubbingBackAndResumingRepeatsTheRun) {
  EventLog events(false);
  // one solver thread, as above
  SimWorker worker(live_run_factory(), std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                   {"solver.threads=1"}, events);
  worker.start(false, 0.0);
  const auto wait = [&worker](const std::function<bool(const WorkerStatus&)>& done) {
    for (int k = 0; k < 12000; ++k) {
      if (done(worker.status())) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  };
  SimCommand history{command::History{1.7e-5, 256}, "test"};  // 42.5 steps of 4e-7 s
  worker.send(history);
  SimCommand step{command::Step{1750}, "test"};  // the crack runs from about step 1600
  worker.send(step);
  ASSERT_TRUE(wait([](const WorkerStatus& s) { return s.step == 1750; }));
  worker.update_snapshot();
  const Snapshot first = worker.snapshot();
  ASSERT_GT(first.broken_bonds, 0);

  // back to the state nearest 3e-4 s (before the crack), shown paused
  SimCommand scrub{command::Scrub{3e-4}, "test"};
  worker.send(scrub);
  ASSERT_TRUE(wait([](const WorkerStatus& s) { return s.scrub >= 0 && s.step < 1000; }));
  worker.update_snapshot();
  EXPECT_EQ(worker.snapshot().broken_bonds, 0);
  EXPECT_NEAR(worker.snapshot().time, 3e-4, 1.7e-5);
  EXPECT_FALSE(worker.status().running);

  // resumed, then stepped to the instant of the first run
  worker.send(SimCommand{command::Resume{}, "test"});
  SimCommand to{command::StepTo{first.time}, "test"};
  worker.send(to);
  ASSERT_TRUE(wait([](const WorkerStatus& s) { return s.commands_applied >= 4 && !s.running && s.step == 1750; }));
  worker.update_snapshot();
  const Snapshot& again = worker.snapshot();
  worker.stop();
  EXPECT_EQ(again.time, first.time);
  EXPECT_EQ(again.broken_bonds, first.broken_bonds);
  EXPECT_EQ(again.px, first.px);
  EXPECT_EQ(again.py, first.py);
  EXPECT_EQ(again.vx, first.vx);
  EXPECT_EQ(again.damage, first.damage);
  EXPECT_EQ(again.series, first.series);
}

}  // namespace
}  // namespace periflex
