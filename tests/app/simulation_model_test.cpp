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

}  // namespace
}  // namespace periflex
