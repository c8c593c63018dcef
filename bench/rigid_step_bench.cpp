// Cost of one step of small rigid mechanisms, where per-step overhead rather than physics
// dominates: the study pendulum (one bar, rk4, Baumgarte), the IFToMM A01 pendulum (point mass,
// rk4, projection) and A02 double four-bar (five bars, rk4, projection, as the scene ships).
#include <benchmark/benchmark.h>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

void step_scene(benchmark::State& state, const std::string& file, const std::string& integrator = "",
                double dt = 0.0) {
  SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/" + file);
  if (!integrator.empty()) scene.solver.integrator = integrator;
  if (dt > 0.0) scene.solver.dt = dt;
  Simulation sim(scene);
  sim.initialize();
  for (auto _ : state) sim.step();
  state.SetItemsProcessed(state.iterations());
}

void BM_Rk4StepPendulum(benchmark::State& state) { step_scene(state, "scenes/studies/models/pendulum.toml"); }
// A01 (point mass, zero inertia: the augmented-matrix path of the dense solve) with rk4 and
// projection at dt = 0.01 s, about the step MuJoCo's RK4 needs for 1e-3 m over 2000 s
void BM_Rk4StepA01(benchmark::State& state) {
  step_scene(state, "scenes/benchmarks/a01_pendulum.toml", "rk4", 0.01);
}
void BM_Rk4StepDoubleFourBar(benchmark::State& state) {
  step_scene(state, "scenes/benchmarks/a02_double_four_bar.toml");
}
BENCHMARK(BM_Rk4StepPendulum);
BENCHMARK(BM_Rk4StepA01);
BENCHMARK(BM_Rk4StepDoubleFourBar);

}  // namespace
}  // namespace periflex
BENCHMARK_MAIN();
