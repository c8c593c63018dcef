// The HHT integrator's first step on the shipped notched plate (4,000 particles, grips turned by
// drivers) at ten times the scene's explicit step: the step that takes the Jacobian's pattern
// from the model, colours it, builds the tangent by coloured finite differences, analyses and
// factorises it. Then the pattern and colouring alone, and a later step, which keeps the tangent.
// One thread, CPU time.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <memory>
#include <string>

#include "core/sparsity_pattern.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"
#include "solve/integrator_hht.h"
#include "solve/system_model.h"

namespace periflex {
namespace {

struct Plate {
  std::unique_ptr<SystemModel> model;
  std::unique_ptr<Dynamics> dynamics;
  OdeState state;
  double dt = 0.0;
};

Plate notched_plate() {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml", {});
  Plate p;
  p.model = build_system_model(scene);
  p.dynamics = std::make_unique<Dynamics>(*p.model);
  p.dynamics->set_correction(scene.solver.correction);
  p.dynamics->analyse(0.0);
  p.state.q = p.model->q0;
  p.state.qd = p.model->qd0;
  p.dynamics->project_positions(0.0, p.state.q, 1e-12, 20);
  p.dynamics->project_velocities(0.0, p.state.q, p.state.qd);
  // ten times the scene's explicit step
  p.dt = 10.0 * scene.solver.dt;
  return p;
}

void BM_HhtFirstStepNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  for (auto _ : state) {
    state.PauseTiming();
    Plate p = notched_plate();
    auto hht = make_hht(kDefaultHhtAlpha);
    state.ResumeTiming();
    hht->step(*p.dynamics, 0.0, p.dt, p.state);
    benchmark::DoNotOptimize(p.state.q.data());
  }
}
BENCHMARK(BM_HhtFirstStepNotchedPlate)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_HhtPatternAndColoursNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  Plate p = notched_plate();
  SparsityPattern pattern;
  size_t colours = 0;
  for (auto _ : state) {
    p.dynamics->jacobian_pattern(0.0, p.state.q, pattern);
    colours = colour_columns(pattern).size();
  }
  state.counters["colours"] = static_cast<double>(colours);
  state.counters["nonzeros"] = static_cast<double>(pattern.nonzeros());
}
BENCHMARK(BM_HhtPatternAndColoursNotchedPlate)->Unit(benchmark::kMillisecond);

void BM_HhtLaterStepNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  Plate p = notched_plate();
  auto hht = make_hht(kDefaultHhtAlpha);
  double t = 0.0;
  hht->step(*p.dynamics, t, p.dt, p.state);
  t += p.dt;
  for (auto _ : state) {
    hht->step(*p.dynamics, t, p.dt, p.state);
    t += p.dt;
  }
}
BENCHMARK(BM_HhtLaterStepNotchedPlate)->Unit(benchmark::kMillisecond)->Iterations(20);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
