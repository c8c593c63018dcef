// Force evaluation per bond, state-based (LPS) against bond-based, on the same grid in the
// configuration the shipped scenes use: the notched steel plate of scenes/notched_plate_models.toml
// (partial volumes, the bond-based surface correction, the notch, fracture on so that the force
// loops also leave the row maxima of the stretch) refined to dx = 0.25 mm (64,000 particles).
// PdBody::add_forces is timed, the call a step makes. Single-thread runs in CPU time, all-thread
// runs in wall-clock time. The counter ns_per_bond is what the two models are compared by. The
// damped variants give both bodies bond damping (eta = 1e3 Pa s), so that the force loops read
// the velocities too, as in a scene with `bond_damping`.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <random>
#include <string>

#include "pd/pd_body.h"

namespace periflex {
namespace {

struct NotchedPlate {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd, g;
  NotchedPlate(bool state_based, bool damped) {
    FlexBodyDef def;
    def.name = std::string(state_based ? "state_based" : "bond_based") + (damped ? "_damped" : "");
    def.shape.kind = ShapeDef::Kind::kBox;
    def.shape.width = 0.1;
    def.shape.height = 0.04;
    def.grid_spacing = 2.5e-4;
    def.thickness = 5e-3;
    def.horizon_ratio = 3.0;
    def.notches.push_back({Vec2(0.0, -0.021), Vec2(0.0, -0.012)});
    def.material.youngs_modulus = 2e11;
    def.material.density = 7850.0;
    def.material.fracture_energy = 1.25e4;
    if (damped) def.bond_damping = 1e3;
    if (state_based) {
      def.material.model = PdMaterialDef::Model::kStateBased;
      def.material.poisson_ratio = 0.3;
    }
    body = PdBody::build(def, 0);
    q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
    // small random strains: no bond near its critical stretch, as in most steps of a run
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1e-8);
    qd.resize(q.size());
    for (int k = 0; k < q.size(); ++k) {
      q[k] += noise(rng);
      qd[k] = noise(rng) * 1e3;
    }
    g = Eigen::VectorXd::Zero(q.size());
  }
};

NotchedPlate& plate(bool state_based, bool damped) {
  static NotchedPlate bond(false, false), state(true, false);
  static NotchedPlate bond_damped(false, true), state_damped(true, true);
  if (damped) return state_based ? state_damped : bond_damped;
  return state_based ? state : bond;
}

void set_threads(benchmark::State& state) {
  omp_set_num_threads(state.range(1) > 0 ? static_cast<int>(state.range(1)) : omp_get_num_procs());
}

// range(0): 1 state-based, 0 bond-based; range(1): threads (0: all); range(2): 1 bond damping
void BM_PlateForces(benchmark::State& state) {
  NotchedPlate& p = plate(state.range(0) == 1, state.range(2) == 1);
  set_threads(state);
  for (auto _ : state) {
    p.body->add_forces(p.q, p.qd, 0.0, p.g);
    benchmark::ClobberMemory();
  }
  const double bonds = static_cast<double>(p.body->bonds().directed_count());
  state.SetLabel(p.body->name());
  state.counters["particles"] = p.body->particle_count();
  state.counters["bond_evals_per_s"] = benchmark::Counter(bonds * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["ns_per_bond"] =
      benchmark::Counter(bonds * state.iterations() * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PlateForces)->Args({0, 1, 0})->Args({1, 1, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlateForces)->Args({0, 0, 0})->Args({1, 0, 0})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlateForces)->Args({0, 1, 1})->Args({1, 1, 1})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
