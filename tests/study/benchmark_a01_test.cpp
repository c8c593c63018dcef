// The IFToMM A01 pendulum as shipped (scenes/benchmarks/a01_pendulum.toml): a point mass with
// zero inertia on a 1 m rod, which the scene loader used to refuse, follows the exact
// Jacobi-elliptic motion over the whole 2000 s (about 850 swings, a few seconds) with the
// scene's own solver settings.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "study/reference_solution.h"

namespace periflex {
namespace {

TEST(BenchmarkA01, PointMassPendulumFollowsTheExactMotion) {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/benchmarks/a01_pendulum.toml");
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_EQ(scene.bodies[0].inertia, 0.0);
  const auto reference = make_pendulum_exact(scene);
  Simulation sim(scene);
  sim.initialize();
  double worst = 0.0;
  for (int k = 1; k <= 40000; ++k) {
    const double t = 0.05 * k;
    sim.advance_to(t);
    const auto p = sim.sample().probe_values;  // x, y, vx, vy, angle
    const auto r = reference->probe_values(t);
    worst = std::max(worst, std::hypot(p[0] - r[0], p[1] - r[1]));
  }
  std::printf("A01 over 2000 s: max position error %.3g m\n", worst);
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace periflex
