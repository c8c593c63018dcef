// Cost of one step of small rigid mechanisms, where per-step overhead rather than physics
// dominates: the study pendulum (one bar, rk4, Baumgarte) and the IFToMM A02 double four-bar
// (five bars, rk4, projection), as the scenes ship.
#include <benchmark/benchmark.h>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

void step_scene(benchmark::State& state, const std::string& file) {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/" + file);
  Simulation sim(scene);
  sim.initialize();
  for (auto _ : state) sim.step();
  state.SetItemsProcessed(state.iterations());
}

void BM_Rk4StepPendulum(benchmark::State& state) { step_scene(state, "scenes/studies/models/pendulum.toml"); }
void BM_Rk4StepDoubleFourBar(benchmark::State& state) {
  step_scene(state, "scenes/benchmarks/a02_double_four_bar.toml");
}
BENCHMARK(BM_Rk4StepPendulum);
BENCHMARK(BM_Rk4StepDoubleFourBar);

}  // namespace
}  // namespace periflex
BENCHMARK_MAIN();
