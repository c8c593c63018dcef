// Saving and restoring the whole state of a 100k-particle run: the notched plate refined to
// dx = 0.2 mm (100k particles, 1.4 M bonds), loaded for 300 steps (moving, not yet cracked).
// Goals: save and restore each under 50 ms, the checkpoint file under 3 MB.
//
//   state_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// SaveState / RestoreState: the in-memory copy (what reset and the window's history take);
// WriteCheckpoint / ReadCheckpoint: with encoding, deflate, the checksum and the file.
// Counter file_MB: the checkpoint's size.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <filesystem>
#include <memory>
#include <string>

#include "output/checkpoint_file.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

// One simulation for every benchmark: building and loading it takes seconds.
Simulation& plate() {
  static std::unique_ptr<Simulation> sim = [] {
    const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                                      {"flex_body.plate.grid_spacing=2e-4", "solver.dt=8e-8", "solver.end_time=1"});
    auto s = std::make_unique<Simulation>(scene);
    s->initialize();
    for (int k = 0; k < 300; ++k) s->step();
    return s;
  }();
  return *sim;
}

std::string file_path() { return (std::filesystem::temp_directory_path() / "periflex_state_bench.pfstate").string(); }

void SaveState(benchmark::State& state) {
  Simulation& sim = plate();
  SimState saved;
  for (auto _ : state) {
    sim.save_state(saved);
    benchmark::DoNotOptimize(saved.q.data());
  }
  state.counters["particles"] = static_cast<double>(sim.info().particles);
  state.counters["broken"] = static_cast<double>(saved.broken_bonds);
}

void RestoreState(benchmark::State& state) {
  Simulation& sim = plate();
  SimState saved;
  sim.save_state(saved);
  for (auto _ : state) sim.restore_state(saved);
}

void WriteCheckpoint(benchmark::State& state) {
  Simulation& sim = plate();
  SimState saved;
  CheckpointHeader header;
  header.program_version = PERIFLEX_VERSION;
  size_t bytes = 0;
  for (auto _ : state) {
    sim.save_state_for_file(saved);
    bytes = write_checkpoint(file_path(), header, saved);
  }
  state.counters["file_MB"] = static_cast<double>(bytes) / 1e6;
}

void ReadCheckpoint(benchmark::State& state) {
  Simulation& sim = plate();
  SimState saved;
  sim.save_state_for_file(saved);
  CheckpointHeader header;
  write_checkpoint(file_path(), header, saved);
  for (auto _ : state) {
    const SimState read = read_checkpoint(file_path(), header);
    sim.restore_state(read);
  }
}

BENCHMARK(SaveState)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(RestoreState)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(WriteCheckpoint)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(ReadCheckpoint)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
