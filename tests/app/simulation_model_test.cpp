// The window's scene loader: a scene picked or reloaded in the window passes the same checks as
// one given on the command line, so a scene over its limits is refused before anything is built.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "app/sim_worker.h"
#include "core/error.h"

namespace periflex {
namespace {

using namespace std::chrono_literals;

const std::string kData = PERIFLEX_TEST_DATA;

TEST(SimulationModel, LoaderRefusesASceneOverItsLimits) {
  const ModelFactory factory = simulation_model_factory();
  try {
    factory.load(kData + "/scenes/app/plate_over_particle_limit.toml", {});
    FAIL() << "a scene of 400 particles with max_particles = 50 was loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_particles"), std::string::npos) << e.what();
  }
}

TEST(SimulationModel, SwitchingToASceneOverItsLimitsKeepsTheCurrentOne) {
  EventLog events(false);
  const std::string start = kData + "/scenes/run/falling_body.toml";
  SimWorker worker(simulation_model_factory(), start, {}, events);
  worker.start(false, 1.0);
  SimCommand load = SimCommand::make(SimCommand::Kind::kLoadScene, "test");
  load.text = kData + "/scenes/app/plate_over_particle_limit.toml";
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
TEST(SimulationModel, ResetRestoresTheStartAndRepeatsTheRun) {
  const ModelFactory factory = simulation_model_factory();
  SceneDef scene = factory.load(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml", {});
  // one solver thread: the ThreadSanitizer build runs this label, and OpenMP's own threads
  // (libgomp is not instrumented) would show as races that are not the program's
  scene.solver.threads = 1;
  std::unique_ptr<SteppedModel> model = factory.build(scene);
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
  std::unique_ptr<SteppedModel> built = factory.build(scene);
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

}  // namespace
}  // namespace periflex
