// Set-up cost of a peridynamic body: the cell-list neighbour search of one million particles
// (goal: under a second) and the whole build (grid, search, bonds, corrections).
#include <benchmark/benchmark.h>
#include <omp.h>

#include "pd/neighbor_search.h"
#include "pd/particle_grid.h"
#include "pd/pd_body.h"

namespace periflex {
namespace {

ShapeDef square(double side) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBox;
  s.width = s.height = side;
  return s;
}

void set_threads(benchmark::State& state) {
  omp_set_num_threads(state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs());
  state.counters["threads"] = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs();
}

// 1000 x 1000 particles, search radius 3.5 dx (horizon ratio 3 plus the partial-volume band).
void BM_NeighborSearchMillion(benchmark::State& state) {
  set_threads(state);
  const ParticleGrid grid = fill_grid(square(1.0), {}, 1e-3);
  for (auto _ : state) {
    NeighborList list = find_neighbors(grid.x, grid.y, 3.5e-3);
    benchmark::DoNotOptimize(list.col.data());
  }
  state.counters["particles"] = grid.size();
  state.counters["particles_per_s"] = benchmark::Counter(grid.size() * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NeighborSearchMillion)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NeighborSearchMillion)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Complete PdBody::build of one million particles.
void BM_BuildMillion(benchmark::State& state) {
  set_threads(state);
  FlexBodyDef def;
  def.name = "bench";
  def.shape = square(1.0);
  def.grid_spacing = 1e-3;
  def.thickness = 1e-3;
  def.material.youngs_modulus = 72e9;
  def.material.density = 2440.0;
  def.material.fracture_energy = 3.8;
  double bytes = 0, particles = 0;
  for (auto _ : state) {
    auto body = PdBody::build(def, 0);
    bytes = static_cast<double>(body->memory_bytes());
    particles = body->particle_count();
  }
  state.counters["bytes_per_particle"] = bytes / particles;
}
BENCHMARK(BM_BuildMillion)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildMillion)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
