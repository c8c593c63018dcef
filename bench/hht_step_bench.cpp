// The HHT integrator's first step on the shipped notched plate (4,000 particles, grips turned by
// drivers) at ten times the scene's explicit step, as a run takes it (Simulation::step): the
// step that takes the Jacobian's pattern from the model, colours it, builds the tangent by
// coloured finite differences, analyses and factorises it. Then the pattern and colouring alone,
// a later step, which keeps the tangent, and the first step with the iteration matrix factorised
// both ways (the free particles' block by Cholesky and the grips by LU, or all of it by LU). One
// thread, CPU time.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <memory>
#include <string>

#include "core/sparsity_pattern.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"
#include "solve/integrator_hht.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

SceneDef hht_plate() {
  // ten times the scene's explicit step of 4e-7 s
  return load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                    {"solver.integrator=hht", "solver.dt=4e-6", "solver.threads=1"});
}

void BM_HhtFirstStepNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  const SceneDef scene = hht_plate();
  for (auto _ : state) {
    state.PauseTiming();
    auto sim = std::make_unique<Simulation>(scene);
    sim->initialize();
    state.ResumeTiming();
    sim->step();
    state.PauseTiming();
    sim.reset();
    state.ResumeTiming();
  }
}
BENCHMARK(BM_HhtFirstStepNotchedPlate)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_HhtPatternAndColoursNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  const auto model = build_system_model(hht_plate());
  Dynamics dynamics(*model);
  dynamics.analyse(0.0);
  SparsityPattern pattern;
  size_t colours = 0;
  for (auto _ : state) {
    dynamics.jacobian_pattern(0.0, model->q0, pattern);
    colours = colour_columns(pattern).size();
  }
  state.counters["colours"] = static_cast<double>(colours);
  state.counters["nonzeros"] = static_cast<double>(pattern.nonzeros());
}
BENCHMARK(BM_HhtPatternAndColoursNotchedPlate)->Unit(benchmark::kMillisecond);

void BM_HhtLaterStepNotchedPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  Simulation sim(hht_plate());
  sim.initialize();
  sim.step();
  for (auto _ : state) sim.step();
}
BENCHMARK(BM_HhtLaterStepNotchedPlate)->Unit(benchmark::kMillisecond)->Iterations(20);

// The equations of motion without their free masses: HHT then factorises S whole by LU.
class WithoutFreeMasses final : public OdeSystem {
 public:
  explicit WithoutFreeMasses(Dynamics& inner) : inner_(inner) {}
  void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    inner_.derivative(t, q, qd, qdd, power);
  }
  bool jacobian_pattern(double t, const Eigen::VectorXd& q, SparsityPattern& pattern) override {
    return inner_.jacobian_pattern(t, q, pattern);
  }

 private:
  Dynamics& inner_;
};

// range(0): 1 the free block by Cholesky where S allows it (what a run does), 0 S whole by LU
void BM_HhtFirstStepFactorisation(benchmark::State& state) {
  omp_set_num_threads(1);
  const SceneDef scene = hht_plate();
  const auto model = build_system_model(scene);
  for (auto _ : state) {
    state.PauseTiming();
    Dynamics dynamics(*model);
    dynamics.set_correction(scene.solver.correction);
    dynamics.analyse(0.0);
    OdeState s;
    s.q = model->q0;
    s.qd = model->qd0;
    WithoutFreeMasses whole(dynamics);
    OdeSystem& system = state.range(0) == 1 ? static_cast<OdeSystem&>(dynamics) : whole;
    auto hht = make_hht(scene.solver);
    state.ResumeTiming();
    hht->step(system, 0.0, scene.solver.dt, s);
  }
  state.SetLabel(state.range(0) == 1 ? "free block by Cholesky" : "whole by LU");
}
BENCHMARK(BM_HhtFirstStepFactorisation)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
