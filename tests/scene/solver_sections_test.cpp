// [scene], [solver] and [solver.correction] read (src/scene/solver_sections.cpp): every key of the
// every-key scene, the defaults of a minimal scene, integers where floats are expected.
#include <gtest/gtest.h>

#include "every_key_scene.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

using test::expect_vec;
using test::RoundTrip;

TEST_F(RoundTrip, SceneAndSolver) {
  EXPECT_EQ(scene.name, "everything");
  EXPECT_EQ(scene.description, "every key");
  EXPECT_EQ(scene.path, "dir/every.toml");
  expect_vec(scene.gravity, 0.5, -1.62);
  const SolverDef& s = scene.solver;
  EXPECT_EQ(s.integrator, "dopri54");
  EXPECT_DOUBLE_EQ(s.dt, 2e-4);
  EXPECT_DOUBLE_EQ(s.end_time, 3.0);
  EXPECT_DOUBLE_EQ(s.rtol, 1e-7);
  EXPECT_DOUBLE_EQ(s.atol, 1e-10);
  EXPECT_DOUBLE_EQ(s.output_interval, 0.02);
  EXPECT_TRUE(s.auto_substep);
  EXPECT_DOUBLE_EQ(s.dt_safety, 0.5);
  EXPECT_EQ(s.threads, 2);
  EXPECT_DOUBLE_EQ(s.hht_alpha, -0.2);
  EXPECT_EQ(s.correction.method, CorrectionDef::Method::kProjection);
  EXPECT_DOUBLE_EQ(s.correction.alpha, 7.0);
  EXPECT_DOUBLE_EQ(s.correction.beta, 8.0);
  EXPECT_DOUBLE_EQ(s.correction.tolerance, 1e-11);
  EXPECT_EQ(s.correction.max_iterations, 20);
}

// Absent sections and keys take the documented defaults.
TEST(SceneDefaults, MinimalSceneTakesDefaults) {
  const SceneDef scene = parse_scene("[[body]]\nname = \"b\"\n", "some/where/minimal.toml");
  EXPECT_EQ(scene.name, "minimal");  // the file stem
  expect_vec(scene.gravity, 0.0, -9.81);
  EXPECT_EQ(scene.solver.integrator, "rk4");
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1e-3);
  EXPECT_EQ(scene.solver.correction.method, CorrectionDef::Method::kBaumgarte);
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 1.0);
  EXPECT_DOUBLE_EQ(scene.bodies[0].inertia, 1.0);
  EXPECT_TRUE(scene.bodies[0].shapes.empty());
}

TEST(SceneFunctions, IntegersAreAcceptedWhereFloatsAreExpected) {
  const SceneDef scene = parse_scene(R"(
[solver]
dt = 1
end_time = 2
[[body]]
name = "a"
mass = 3
position = [1, 2]
)", "x.toml");
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1.0);
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 3.0);
  expect_vec(scene.bodies[0].position, 1.0, 2.0);
}

}  // namespace
}  // namespace periflex
