// The Simulation facade (solve/simulation.h): a scene's solver.threads sets the team of the
// simulation's own calls and leaves the calling thread's OpenMP setting as it found it.
#include "solve/simulation.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <string>

#include "core/thread_pool.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

TEST(Simulation, ItsThreadCountStaysItsOwn) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(2);
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                                    {"solver.threads=1"});
  {
    Simulation sim(scene);
    EXPECT_EQ(omp_get_max_threads(), 2) << "building it";
    for (int k = 0; k < 3; ++k) sim.step();
    (void)sim.sample();
    SimState state;
    sim.save_state(state);
    sim.restore_state(state);
    EXPECT_EQ(omp_get_max_threads(), 2) << "stepping, sampling, saving and restoring it";
    EXPECT_EQ(team_size(), 2);
  }
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace periflex
