// Bond-force throughput of the peridynamic kernel: a square glass plate at horizon ratio 3,
// particles displaced by a small random field, forces evaluated on 1 thread and on all; and the
// body of scenes/glass_branching.toml as shipped (partial volumes, surface correction, fracture
// on: the force evaluation that breaks bonds), through PdBody::add_forces as the solver calls it.
// Counters: bond evaluations per second (each stored direction counts once, the work the
// gather loop does), per-core rate, bytes per particle and per bond of the whole body.
// The single-thread runs are timed in CPU time (what one core delivers, unaffected by other
// processes waiting for the same cores); the all-thread runs in wall-clock time.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <random>

#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

// A plate of side x side particles, dx = 1 mm, and positions perturbed by 1e-6 m.
struct Plate {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd, g;
  explicit Plate(int side) {
    FlexBodyDef def;
    def.name = "bench";
    def.shape.kind = ShapeDef::Kind::kBox;
    def.shape.width = def.shape.height = side * 1e-3;
    def.grid_spacing = 1e-3;
    def.thickness = 1e-3;
    def.material.youngs_modulus = 72e9;
    def.material.density = 2440.0;
    def.material.fracture_energy = 3.8;
    body = PdBody::build(def, 0);
    q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1e-6);
    qd.resize(q.size());
    for (int k = 0; k < q.size(); ++k) {
      q[k] += noise(rng);
      qd[k] = noise(rng) * 1e3;
    }
    g = Eigen::VectorXd::Zero(q.size());
  }
};

Plate& plate() {
  static Plate p(500);  // 250,000 particles, about 8.6 million stored bond directions
  return p;
}

void set_threads(benchmark::State& state) {
  omp_set_num_threads(state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs());
}

void report(benchmark::State& state, const Plate& p) {
  const double bonds = static_cast<double>(p.body->bonds().directed_count());
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs();
  state.counters["threads"] = threads;
  state.counters["bond_evals_per_s"] = benchmark::Counter(bonds * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["bond_evals_per_s_per_core"] =
      benchmark::Counter(bonds * state.iterations() / threads, benchmark::Counter::kIsRate);
  state.counters["bytes_per_particle"] = static_cast<double>(p.body->memory_bytes()) / p.body->particle_count();
  const double bond_bytes = static_cast<double>(p.body->bonds().bytes() + p.body->bond_state().bytes());
  state.counters["bytes_per_bond"] = bond_bytes / bonds;
  state.counters["bonds_per_particle"] = bonds / p.body->particle_count();
}

// Elastic bond forces (the kernel every explicit step runs).
void BM_BondForces(benchmark::State& state) {
  Plate& p = plate();
  set_threads(state);
  for (auto _ : state) {
    add_bond_forces(p.body->bonds(), p.body->bond_state(), p.q.data(), p.g.data());
    benchmark::ClobberMemory();
  }
  report(state, p);
}
BENCHMARK(BM_BondForces)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BondForces)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Elastic bond forces that also leave each row's largest stretch (what a body with fracture
// on runs, so that update_fracture at the same positions needs no pass of its own).
void BM_BondForcesWithStretchMaxima(benchmark::State& state) {
  Plate& p = plate();
  set_threads(state);
  std::vector<double> most(p.body->particle_count());
  for (auto _ : state) {
    add_bond_forces(p.body->bonds(), p.body->bond_state(), p.q.data(), p.g.data(), most.data());
    benchmark::ClobberMemory();
  }
  report(state, p);
}
BENCHMARK(BM_BondForcesWithStretchMaxima)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BondForcesWithStretchMaxima)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Bond forces with viscous bond damping (needs velocities).
void BM_DampedBondForces(benchmark::State& state) {
  Plate& p = plate();
  set_threads(state);
  for (auto _ : state) {
    add_damped_bond_forces(p.body->bonds(), p.body->bond_state(), p.q.data(), p.qd.data(), 1e-8, p.g.data());
    benchmark::ClobberMemory();
  }
  report(state, p);
}
BENCHMARK(BM_DampedBondForces)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DampedBondForces)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// The stand-alone stretch check of update_fracture (when no force evaluation at the same
// positions preceded it; nothing breaks here: the field is far below s0).
void BM_FractureCheck(benchmark::State& state) {
  Plate& p = plate();
  set_threads(state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.body->update_fracture(p.q));
  }
  report(state, p);
}
BENCHMARK(BM_FractureCheck)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FractureCheck)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// The glass-branching body as the scene ships it (36,000 particles, 1.27 million stored bond
// directions), positions displaced by 1e-9 m at random: far below s0, so nothing breaks and every
// repetition does the same work.
struct ShippedGlass {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd, g;
  ShippedGlass() {
    const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/glass_branching.toml");
    body = PdBody::build(scene.flex_bodies.at(0), 0);
    q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1e-9);
    for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
    qd = Eigen::VectorXd::Zero(q.size());
    g = Eigen::VectorXd::Zero(q.size());
  }
};

ShippedGlass& shipped_glass() {
  static ShippedGlass p;
  return p;
}

void report_shipped(benchmark::State& state, const ShippedGlass& p) {
  const double bonds = static_cast<double>(p.body->bonds().directed_count());
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs();
  state.counters["threads"] = threads;
  state.counters["bond_evals_per_s"] = benchmark::Counter(bonds * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["bond_evals_per_s_per_core"] =
      benchmark::Counter(bonds * state.iterations() / threads, benchmark::Counter::kIsRate);
}

// The body's whole force evaluation with fracture on (bonds past s0 would break in it), then the
// fracture update at the same positions, as a velocity-Verlet step runs them.
void BM_ShippedGlassForces(benchmark::State& state) {
  ShippedGlass& p = shipped_glass();
  set_threads(state);
  for (auto _ : state) {
    p.body->add_forces(p.q, p.qd, 0.0, p.g);
    benchmark::DoNotOptimize(p.body->update_fracture(p.q));
    benchmark::ClobberMemory();
  }
  if (p.body->broken_bond_count() != 0) state.SkipWithError("bonds broke: the benchmark field is too large");
  report_shipped(state, p);
}
BENCHMARK(BM_ShippedGlassForces)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShippedGlassForces)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// The strain energy of the same body (the solver's energy checks and every output row).
void BM_ShippedGlassStrainEnergy(benchmark::State& state) {
  ShippedGlass& p = shipped_glass();
  set_threads(state);
  for (auto _ : state) benchmark::DoNotOptimize(p.body->potential_energy(p.q));
  report_shipped(state, p);
}
BENCHMARK(BM_ShippedGlassStrainEnergy)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
