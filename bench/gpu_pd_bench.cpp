// Bond evaluations per second of a flexible body's force pass on the GPU (OpenGL compute, fp64 and
// fp32, gpu/gl_bond_force_device.h) and on the CPU, on the same bodies: square glass plates of
// side x side particles (dx = 1 mm, horizon 3 dx, fracture on: the evaluation that breaks bonds,
// through PdBody::add_forces as the solver calls it) and the body of scenes/glass_branching.toml as
// shipped. Positions are displaced by a small random field, far below s0, so every repetition does
// the same work. The GPU figures: the whole evaluation as it runs today (positions up, the
// dispatch, forces and break flags back), and the pass alone with the state resident. Counters: bond_evals_per_s (each stored direction once).
// Wall-clock time throughout (the GPU works while the calling thread waits).
// Arguments: the plate side, then the CPU threads (0: all cores), or on the GPU the precision (0:
// fp64, 1: fp32, the displacement form) and whether the state is resident (see BM_GpuForcePass).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <map>
#include <memory>
#include <random>
#include <string>

#include "core/resources.h"
#include "gpu/gl_bond_force_device.h"
#include "pd/pd_body.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

// A body with its displaced positions and velocities and a force array.
struct Body {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd, g;
  GlBondForceDevice* device = nullptr;  // when on the GPU
  explicit Body(const FlexBodyDef& def) {
    body = PdBody::build(def, 0);
    q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 1e-9);
    qd.resize(q.size());
    for (int k = 0; k < q.size(); ++k) {
      q[k] += noise(rng);
      qd[k] = noise(rng) * 1e3;
    }
    g = Eigen::VectorXd::Zero(q.size());
  }
};

FlexBodyDef glass_square(int side) {
  FlexBodyDef def;
  def.name = "bench";
  def.shape.kind = ShapeDef::Kind::kBox;
  def.shape.width = def.shape.height = side * 1e-3;
  def.grid_spacing = 1e-3;
  def.thickness = 1e-3;
  def.material.youngs_modulus = 72e9;
  def.material.density = 2440.0;
  def.material.fracture_energy = 3.8;
  def.fracture = true;
  return def;
}

FlexBodyDef shipped_glass() {
  return load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/glass_branching.toml").flex_bodies.at(0);
}

// The compute context, made once; null (the GPU benchmarks skip) where none can be made.
std::shared_ptr<GlComputeContext> compute_context(std::string& why) {
  static std::string reason;
  static std::shared_ptr<GlComputeContext> context = [] {
    try {
      return std::make_shared<GlComputeContext>(find_resource_root());
    } catch (const std::exception& e) {
      reason = e.what();
      return std::shared_ptr<GlComputeContext>();
    }
  }();
  why = reason;
  return context;
}

// Where a body's forces run: the CPU, or the GPU in fp64 or fp32.
enum Path { kCpu = -1, kGpuFp64 = 0, kGpuFp32 = 1 };

// One body per (side, path), kept between the benchmarks of the same size; side 0: the shipped glass.
Body& body(int side, int path) {
  static std::map<std::pair<int, int>, std::unique_ptr<Body>> bodies;
  auto& slot = bodies[{side, path}];
  if (!slot) {
    // one size at a time in memory: the larger plates hold gigabytes
    bodies.clear();
    auto& fresh = bodies[{side, path}];
    fresh = std::make_unique<Body>(side > 0 ? glass_square(side) : shipped_glass());
    if (path != kCpu) {
      std::string why;
      auto device = std::make_unique<GlBondForceDevice>(
          compute_context(why), path == kGpuFp32 ? DevicePrecision::kFp32 : DevicePrecision::kFp64);
      fresh->device = device.get();
      fresh->body->use_bond_force_device(std::move(device));
    }
    return *fresh;
  }
  return *slot;
}

void report(benchmark::State& state, const Body& b, const std::string& label) {
  const double bonds = static_cast<double>(b.body->bonds().directed_count());
  state.counters["particles"] = b.body->particle_count();
  state.counters["bond_evals_per_s"] = benchmark::Counter(bonds * state.iterations(), benchmark::Counter::kIsRate);
  state.SetLabel(label);
}

void BM_CpuForcePass(benchmark::State& state) {
  const int threads = state.range(1) > 0 ? static_cast<int>(state.range(1)) : omp_get_num_procs();
  omp_set_num_threads(threads);
  Body& b = body(static_cast<int>(state.range(0)), kCpu);
  for (auto _ : state) {
    b.body->add_forces(b.q, b.qd, 0.0, b.g);
    benchmark::ClobberMemory();
  }
  report(state, b, "cpu, " + std::to_string(threads) + " threads");
}

// The pass on the GPU: with the state's transfers as the solver runs it today (resident = 0:
// positions up, forces and break flags back), or alone with the state already on the GPU
// (resident = 1: nothing crosses the bus, what a step costs the GPU once the state stays there).
void BM_GpuForcePass(benchmark::State& state) {
  std::string why;
  if (!compute_context(why)) {
    state.SkipWithError(("no OpenGL compute context: " + why).c_str());
    return;
  }
  Body& b = body(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const bool resident = state.range(2) == 1;
  b.body->add_forces(b.q, b.qd, 0.0, b.g);  // positions up, the pass's settings
  for (auto _ : state) {
    if (resident) {
      b.device->repeat_last_pass();
    } else {
      b.body->add_forces(b.q, b.qd, 0.0, b.g);
      benchmark::ClobberMemory();
    }
  }
  report(state, b, std::string(resident ? "resident; " : "with transfers; ") + b.body->bond_force_device()->description());
}

// sides: 128 (16k particles), 512 (262k), 1024 (1M), 2048 (4.2M), 4096 (16.8M, GPU only); 0: the
// shipped glass (36k)
constexpr int kSides[] = {0, 128, 512, 1024, 2048, 4096};
void cpu_sizes(benchmark::internal::Benchmark* b) {
  for (int side : kSides) {
    if (side > 2048) continue;  // 16.8M particles: seconds a pass on the CPU
    b->Args({side, 1});
    b->Args({side, 0});
  }
}
// in the order that builds each body once: side, precision, then the two ways
void gpu_sizes(benchmark::internal::Benchmark* b) {
  for (int side : kSides)
    for (int path : {kGpuFp64, kGpuFp32}) {
      b->Args({side, path, 0});
      b->Args({side, path, 1});
    }
}
BENCHMARK(BM_CpuForcePass)->Apply(cpu_sizes)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GpuForcePass)->Apply(gpu_sizes)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
