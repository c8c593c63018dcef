// Points that are not a grid: 250 000 points of a 500 x 500 grid, each moved by up to a quarter
// of a spacing in x and y (a jittered grid, as a point file from a mesher or a perturbed
// discretisation brings), against the grid itself. The neighbour search (radius 3.5 spacings:
// horizon ratio 3 plus the partial-volume band) per bond found, and the force pass of a glass
// body built on each (bond-based, partial volumes and surface correction on, the fracture check
// on) per stored bond. Goal: the jittered set at most 1.5 times the grid's time per bond.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <random>

#include "pd/neighbor_search.h"
#include "pd/particle_grid.h"
#include "pd/pd_body.h"

namespace periflex {
namespace {

constexpr double kSpacing = 1e-3;

ParticleGrid points(bool jittered) {
  ShapeDef square;
  square.kind = ShapeDef::Kind::kBox;
  square.width = square.height = 500 * kSpacing;
  ParticleGrid grid = fill_grid(square, {}, kSpacing);
  if (jittered) {
    std::mt19937 random(36);
    std::uniform_real_distribution<double> shift(-0.25 * kSpacing, 0.25 * kSpacing);
    for (int i = 0; i < grid.size(); ++i) {
      grid.x[i] += shift(random);
      grid.y[i] += shift(random);
    }
  }
  return grid;
}

// Arg 0: the grid; 1: jittered. One thread: the cost per bond, not the machine's parallelism.
void BM_NeighborSearch250k(benchmark::State& state) {
  omp_set_num_threads(1);
  const ParticleGrid grid = points(state.range(0) != 0);
  double bonds = 0.0;
  for (auto _ : state) {
    NeighborList list = find_neighbors(grid.x, grid.y, 3.5 * kSpacing);
    bonds = static_cast<double>(list.col.size());
    benchmark::DoNotOptimize(list.col.data());
  }
  state.counters["particles"] = grid.size();
  state.counters["bonds_per_particle"] = bonds / grid.size();
  state.counters["ns_per_bond"] =
      benchmark::Counter(bonds * state.iterations() * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_NeighborSearch250k)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

// Arg 0: the grid; 1: jittered (the body's own jitter key, a quarter spacing). One thread.
void BM_ForcePass250k(benchmark::State& state) {
  omp_set_num_threads(1);
  FlexBodyDef def;
  def.name = "plate";
  def.shape.kind = ShapeDef::Kind::kBox;
  def.shape.width = def.shape.height = 500 * kSpacing;
  def.grid_spacing = kSpacing;
  def.thickness = 1e-3;
  def.material.youngs_modulus = 72e9;
  def.material.density = 2440.0;
  def.material.fracture_energy = 3.8;
  def.jitter = state.range(0) != 0 ? 0.25 : 0.0;
  auto body = PdBody::build(def, 0);
  const std::vector<double>& x = body->reference_positions();
  // a uniform stretch of a tenth of the critical stretch: nothing breaks between passes, no row
  // comes near the break test's exact walk
  const double stretch = 0.1 * body->critical_stretch();
  Eigen::VectorXd q(x.size()), qd = Eigen::VectorXd::Zero(x.size()), g(x.size());
  for (size_t k = 0; k < x.size(); ++k) q[k] = x[k] * (1.0 + stretch);
  for (auto _ : state) {
    g.setZero();
    body->add_forces(q, qd, 0.0, g);
    benchmark::DoNotOptimize(g.data());
  }
  const std::vector<uint8_t>& broken = body->bond_state().broken;
  if (std::count(broken.begin(), broken.end(), 0) != static_cast<long>(broken.size()))
    state.SkipWithError("bonds broke during the passes");
  const double bonds = static_cast<double>(body->bonds().directed_count());
  state.counters["particles"] = body->particle_count();
  state.counters["bonds_per_particle"] = bonds / body->particle_count();
  state.counters["ns_per_bond"] =
      benchmark::Counter(bonds * state.iterations() * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ForcePass250k)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
