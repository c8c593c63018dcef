// The neighbour search on points that are not a grid: 250 000 points of a 500 x 500 grid, each
// moved by up to a quarter of a spacing in x and y (a jittered grid, as a point file from a
// mesher or a perturbed discretisation brings), against the grid itself. Reported per bond
// found (goal: the jittered set at most 1.5 times the grid's time per bond). The search radius
// is 3.5 spacings: horizon ratio 3 plus the partial-volume band.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <random>

#include "pd/neighbor_search.h"
#include "pd/particle_grid.h"

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

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
