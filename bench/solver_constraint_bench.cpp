// Cost of the constraint solve as the number of constrained coordinates grows: a strip of
// particles held entirely by a rigid-flexible joint to a massless virtual body that a driver
// turns about a pin. The sparse augmented system should cost about linearly in the particles.
#include <benchmark/benchmark.h>

#include "solve/kkt_solver.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

SceneDef attached_strip(int columns) {
  const double dx = 1e-3;
  SceneDef s;
  s.name = "bench";
  s.solver.integrator = "verlet";
  s.solver.dt = 1e-6;
  s.solver.correction.method = CorrectionDef::Method::kBaumgarte;
  BodyDef hand;
  hand.name = "hand";
  hand.mass = 0.0;
  hand.inertia = 0.0;
  hand.is_virtual = true;
  s.bodies.push_back(hand);
  FlexBodyDef f;
  f.name = "strip";
  f.shape.kind = ShapeDef::Kind::kBox;
  f.shape.center = Vec2(0.5 * columns * dx, 0.0);
  f.shape.width = columns * dx;
  f.shape.height = 4 * dx;
  f.grid_spacing = dx;
  f.thickness = dx;
  f.material.youngs_modulus = 1e6;
  f.material.density = 1000.0;
  f.fracture = false;
  s.flex_bodies.push_back(f);
  AttachmentDef a;
  a.name = "grip";
  a.body = "hand";
  a.flex_body = "strip";
  a.region = f.shape;
  a.region.width += dx;
  a.region.height += dx;
  s.attachments.push_back(a);
  JointDef pin;
  pin.name = "pin";
  pin.body_i = "ground";
  pin.body_j = "hand";
  s.joints.push_back(pin);
  DriverDef turn;
  turn.name = "turn";
  turn.body_i = "hand";
  turn.function = TimeFunction::linear(0.0, 1.0);
  s.drivers.push_back(turn);
  return s;
}

// Wall time of the constraint solve per step, reported as a counter; the benchmark time is
// the whole step (forces included).
void BM_AttachedStripStep(benchmark::State& state) {
  Simulation sim(attached_strip(static_cast<int>(state.range(0))));
  sim.initialize();
  for (auto _ : state) sim.step();
  const double steps = static_cast<double>(sim.step_count());
  state.counters["constraint_s_per_step"] = sim.timing().constraints / steps;
  state.counters["constrained_coordinates"] = static_cast<double>(sim.info().coordinates);
  state.SetComplexityN(sim.info().coordinates);
}
BENCHMARK(BM_AttachedStripStep)->RangeMultiplier(4)->Range(16, 1024)->Complexity(benchmark::oN)
    ->Unit(benchmark::kMicrosecond);

// The augmented system alone: n particles (mass 1e-6) held by one free massless virtual body,
// 2 equations each. Factorisation time per particle should stay flat as n grows.
void BM_KktFactorizeAttachedParticles(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Eigen::VectorXd w = Eigen::VectorXd::Constant(3 + 2 * n, 1e-6);
  w.head(3).setZero();
  Triplets j;
  for (int p = 0; p < n; ++p) {
    for (int k = 0; k < 2; ++k) {
      const int row = 2 * p + k;
      j.emplace_back(row, k, 1.0);
      j.emplace_back(row, 2, 0.3 * (k ? 1 : -1) * (p % 7 + 1));
      j.emplace_back(row, 3 + 2 * p + k, -1.0);
    }
  }
  KktSolver solver;
  for (auto _ : state) benchmark::DoNotOptimize(solver.factorize(w, j, 2 * n));
  state.SetComplexityN(n);
}
BENCHMARK(BM_KktFactorizeAttachedParticles)->RangeMultiplier(4)->Range(64, 16384)->Complexity(benchmark::oN)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
