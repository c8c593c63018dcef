// The elastic bond forces of the body of scenes/glass_branching.toml as shipped (36,000 particles,
// 1.27 million stored bond directions, partial volumes and surface correction in the stiffness),
// one thread, CPU time: the hand-written row loops of src/pd (AVX-512, AVX2, portable) against
// one source written with xsimd (pd_simd_library_rows.cpp) compiled for AVX-512 and for AVX2,
// with the neighbours' coordinates read lane by lane or gathered by the library. Each benchmark
// first compares its forces with the portable loop's (counter diff: largest difference over the
// largest force).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "pd_simd_library_rows.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

struct ShippedGlass {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, g, reference;
  ShippedGlass() {
    const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/glass_branching.toml");
    body = PdBody::build(scene.flex_bodies.at(0), 0);
    q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1e-9);
    for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
    g = Eigen::VectorXd::Zero(q.size());
    reference = Eigen::VectorXd::Zero(q.size());
    set_vector_kernels(VectorKernels::kPortable);
    add_bond_forces(body->bonds(), body->bond_state(), q.data(), reference.data());
    set_vector_kernels(VectorKernels::kAvx512);
  }
};

ShippedGlass& glass() {
  static ShippedGlass p;
  return p;
}

bench::RowArrays arrays(const BondStore& b, const BondState& live) {
  return {b.row.data(), b.neighbor.data(), b.length_class.data(), b.inv_length_table.data(), live.stiffness.data()};
}

using Rows = void (*)(int, int, const bench::RowArrays&, const double*, double*);

// range(0): 0 hand AVX-512, 1 hand AVX2, 2 portable, 3 xsimd AVX-512, 4 xsimd AVX2,
// 5 xsimd AVX-512 with gathers, 6 xsimd AVX2 with gathers
void BM_GlassElasticForces(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  if (which == 0 && !__builtin_cpu_supports("avx512bw")) return state.SkipWithError("no AVX-512");
  if ((which == 3 || which == 5) && !__builtin_cpu_supports("avx512bw")) return state.SkipWithError("no AVX-512");
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return state.SkipWithError("no AVX2");
  ShippedGlass& p = glass();
  omp_set_num_threads(1);
  const BondStore& bonds = p.body->bonds();
  const bench::RowArrays r = arrays(bonds, p.body->bond_state());
  const Rows library[] = {bench::elastic_rows_xsimd_avx512, bench::elastic_rows_xsimd_avx2,
                          bench::elastic_rows_xsimd_gather_avx512, bench::elastic_rows_xsimd_gather_avx2};
  const VectorKernels hand[] = {VectorKernels::kAvx512, VectorKernels::kAvx2, VectorKernels::kPortable};
  auto run = [&](Eigen::VectorXd& out) {
    if (which < 3)
      add_bond_forces(bonds, p.q.data(), out.data());
    else
      library[which - 3](0, bonds.particle_count(), r, p.q.data(), out.data());
  };
  if (which < 3) set_vector_kernels(hand[which]);
  Eigen::VectorXd check = Eigen::VectorXd::Zero(p.q.size());
  run(check);
  // the field is tiny (1e-9 m), so each force is a sum with heavy cancellation: the difference is
  // reported against the largest force (the hand-written loops differ from each other by about 1e-9)
  const double diff = (check - p.reference).cwiseAbs().maxCoeff() / p.reference.cwiseAbs().maxCoeff();
  if (!(diff <= 1e-6)) state.SkipWithError("forces differ");
  for (auto _ : state) {
    run(p.g);
    benchmark::ClobberMemory();
  }
  set_vector_kernels(VectorKernels::kAvx512);
  const double n = static_cast<double>(bonds.directed_count());
  static const char* names[] = {"hand AVX-512", "hand AVX2", "portable", "xsimd AVX-512", "xsimd AVX2",
                                "xsimd AVX-512 gather", "xsimd AVX2 gather"};
  state.SetLabel(names[which]);
  state.counters["diff"] = diff;
  state.counters["ns_per_bond"] =
      benchmark::Counter(n * state.iterations() * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_GlassElasticForces)->DenseRange(0, 6)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
