// What the rigid-body inspector costs the simulation thread: while it is open every snapshot
// carries the joints' reactions, one more solve of the equations of motion at that state; while
// it is closed none is made. On the slider-crank and the four-bar: a snapshot closed and open,
// and one step for scale. The simulation thread makes at most 120 snapshots a second.
#include <benchmark/benchmark.h>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

// A simulation of the scene after 200 steps, away from its initial state.
std::unique_ptr<Simulation> stepped(const char* file) {
  auto sim = std::make_unique<Simulation>(load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + file));
  sim->initialize();
  for (int k = 0; k < 200; ++k) sim->step();
  return sim;
}

void snapshot(benchmark::State& state, const char* file) {
  const auto sim = stepped(file);
  Snapshot s;
  s.with_reactions = state.range(0) != 0;
  for (auto _ : state) {
    sim->fill_snapshot(s);
    benchmark::DoNotOptimize(s.reactions.data());
  }
  if (s.with_reactions == s.reactions.empty()) state.SkipWithError("reactions present exactly when asked for: no");
  state.SetLabel(s.with_reactions ? "inspector open" : "inspector closed");
}

void step(benchmark::State& state, const char* file) {
  const auto sim = stepped(file);
  for (auto _ : state) sim->step();
}

void BM_SnapshotSliderCrank(benchmark::State& state) { snapshot(state, "slider_crank.toml"); }
void BM_SnapshotFourBar(benchmark::State& state) { snapshot(state, "four_bar.toml"); }
void BM_StepSliderCrank(benchmark::State& state) { step(state, "slider_crank.toml"); }
void BM_StepFourBar(benchmark::State& state) { step(state, "four_bar.toml"); }
BENCHMARK(BM_SnapshotSliderCrank)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SnapshotFourBar)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepSliderCrank)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepFourBar)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
