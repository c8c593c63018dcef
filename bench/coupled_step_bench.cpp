// Cost of one whole coupled step (bond forces + constraint solve + integration + fracture check)
// of the notched plate, refined to about 100k particles, on one and on two threads; and the cost
// of the constraint solve against the number of attached particles.
//
//   coupled_step_bench --benchmark_counters_tabular=true
//
// Counters: steps/s, the share of each part of the step (from Simulation::timing(), plus the
// output a run writes: a sample and a snapshot every output_interval of simulated time), the
// particle and attached-particle counts, and for the attachment sweep the constraint time per step.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

std::string scene_path() { return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml"; }

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// The notched plate at grid spacing dx (time step scaled with it), grips `grip_columns` wide,
// on `threads` threads. Fracture stays on: the check is part of every step.
SceneDef refined_plate(double dx, int grip_columns, int threads) {
  const double coarse_dx = 1e-3, coarse_dt = 4e-7;
  const double grip = grip_columns * dx;
  std::vector<std::string> overrides = {
      "flex_body.plate.grid_spacing=" + number(dx),
      "solver.dt=" + number(coarse_dt * dx / coarse_dx),
      "solver.threads=" + std::to_string(threads),
      "solver.end_time=1",
  };
  // grips of the requested width flush with the plate's sides
  const double left = -0.05 + 0.5 * grip, right = 0.05 - 0.5 * grip;
  overrides.push_back("attachment.left_grip_joint.region={type=\"box\", center=[" + number(left) +
                      ", 0.0], width=" + number(grip) + ", height=0.042}");
  overrides.push_back("attachment.right_grip_joint.region={type=\"box\", center=[" + number(right) +
                      ", 0.0], width=" + number(grip) + ", height=0.042}");
  return load_scene(scene_path(), overrides);
}

// Steps a model that is built once per configuration (building 100k particles takes a while).
void run_steps(benchmark::State& state, const SceneDef& scene) {
  // the thread count is set here as well as in the scene, so the sweep holds whatever the
  // solver does with solver.threads
  if (scene.solver.threads > 0) omp_set_num_threads(scene.solver.threads);
  Simulation sim(scene);
  sim.initialize();
  // a few steps first so that the constraint pattern is analysed outside the timed loop
  for (int k = 0; k < 3; ++k) sim.step();
  const Simulation::Timing before = sim.timing();
  const long steps_before = sim.step_count();
  // output as `periflex run` writes it: a sample (series.csv row) and a snapshot (frames, VTK)
  // every output_interval of simulated time
  const long output_every =
      std::max(1L, static_cast<long>(std::llround(scene.solver.output_interval / scene.solver.dt)));
  double output = 0.0;
  Snapshot snapshot;
  for (auto _ : state) {
    sim.step();
    if (sim.step_count() % output_every == 0) {
      const auto start = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(sim.sample());
      sim.fill_snapshot(snapshot);
      output += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  }
  const Simulation::Timing after = sim.timing();
  const double steps = static_cast<double>(sim.step_count() - steps_before);
  const double forces = after.forces - before.forces, constraints = after.constraints - before.constraints;
  const double integration = after.integration - before.integration, fracture = after.fracture - before.fracture;
  const double total = forces + constraints + integration + fracture + output;
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(sim.info().particles);
  state.counters["forces%"] = total > 0 ? 100.0 * forces / total : 0.0;
  state.counters["constraints%"] = total > 0 ? 100.0 * constraints / total : 0.0;
  state.counters["integration%"] = total > 0 ? 100.0 * integration / total : 0.0;
  state.counters["fracture%"] = total > 0 ? 100.0 * fracture / total : 0.0;
  state.counters["output%"] = total > 0 ? 100.0 * output / total : 0.0;
  state.counters["constraint_us/step"] = steps > 0 ? 1e6 * constraints / steps : 0.0;
}

// Whole coupled step at dx = 0.2 mm (500 x 200 = 100k particles), 3-column grips; arg = threads.
void BM_NotchedPlateStep100k(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  run_steps(state, refined_plate(2e-4, 3, threads));
}
BENCHMARK(BM_NotchedPlateStep100k)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->MinTime(3.0);

// Constraint-solve cost against attached particles: dx = 0.5 mm (200 x 80 = 16k particles),
// grips 3 to 24 columns wide (2 x 240 to 2 x 1920 attached particles); arg = columns. Building
// the model, not stepping it, limits the sweep: the redundancy analysis at set-up grows about
// with the cube of the attached particles (12 s at 2 x 960 on this machine).
void BM_ConstraintSolveVsAttachedParticles(benchmark::State& state) {
  const int columns = static_cast<int>(state.range(0));
  const SceneDef scene = refined_plate(5e-4, columns, 1);
  state.counters["attached"] = 2.0 * columns * 80;
  run_steps(state, scene);
}
BENCHMARK(BM_ConstraintSolveVsAttachedParticles)->Arg(3)->Arg(6)->Arg(12)->Arg(24)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
