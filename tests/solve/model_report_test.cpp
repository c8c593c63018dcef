// The model report at set-up (src/solve/model_report.cpp): redundant constraints, bodies whose
// motion nothing determines, and the list of active modules.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

bool has(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// Parallelogram four-bar: pivots (0,0) and (1,0), crank and rocker of length 0.5 at 60 degrees,
// coupler of length 1. With `redundant`, an extra massless link of length 0.5 joins the ground
// at (0.5, 0) to the middle of the coupler, parallel to the crank: its equation depends on the
// others in every position of a parallelogram.
SceneDef parallelogram(bool redundant) {
  SceneDef s = test::empty_scene("rk4", 1e-3, CorrectionDef::Method::kProjection);
  const double a = kPi / 3, r = 0.5;
  const Vec2 tip(r * std::cos(a), r * std::sin(a));
  s.bodies.push_back(test::body("crank", 1.0, 0.02, tip / 2, a));
  s.bodies.push_back(test::body("coupler", 2.0, 0.17, tip + Vec2(0.5, 0.0), 0.0));
  s.bodies.push_back(test::body("rocker", 1.0, 0.02, Vec2(1.0, 0.0) + tip / 2, a));
  s.joints.push_back(test::revolute("A", "ground", "crank", Vec2::Zero(), Vec2(-r / 2, 0.0)));
  s.joints.push_back(test::revolute("B", "crank", "coupler", Vec2(r / 2, 0.0), Vec2(-0.5, 0.0)));
  s.joints.push_back(test::revolute("C", "coupler", "rocker", Vec2(0.5, 0.0), Vec2(r / 2, 0.0)));
  s.joints.push_back(test::revolute("D", "rocker", "ground", Vec2(-r / 2, 0.0), Vec2(1.0, 0.0)));
  if (redundant) {
    JointDef link;
    link.kind = JointDef::Kind::kRevoluteRevolute;
    link.name = "extra_link";
    link.body_i = "ground";
    link.body_j = "coupler";
    link.point_i = Vec2(0.5, 0.0);
    link.point_j = Vec2::Zero();
    s.joints.push_back(link);
  }
  s.probes.push_back({"crank_tip", "crank", Vec2(r / 2, 0.0), {}});
  return s;
}

TEST(Redundancy, ParallelogramWithExtraLinkReportsOneRedundantEquation) {
  Simulation plain(parallelogram(false));
  Simulation extra(parallelogram(true));
  EXPECT_EQ(plain.info().redundant_equations, 0);
  EXPECT_EQ(plain.info().degrees_of_freedom, 1);
  // 9 coordinates, 9 equations of rank 8
  EXPECT_EQ(extra.info().constraint_equations, 9);
  EXPECT_EQ(extra.info().redundant_equations, 1);
  EXPECT_EQ(extra.info().redundant_constraints.size(), 1u);
  EXPECT_EQ(extra.info().degrees_of_freedom, 1);
  bool warned = false;
  for (const auto& w : extra.info().warnings) warned |= w.find("redundant") != std::string::npos;
  EXPECT_TRUE(warned);

  // the motion under gravity is the motion of the non-redundant model
  plain.initialize();
  extra.initialize();
  double worst = 0.0;
  for (int k = 1; k <= 50; ++k) {
    plain.advance_to(0.02 * k);
    extra.advance_to(0.02 * k);
    const auto a = plain.sample().probe_values, b = extra.sample().probe_values;
    worst = std::max({worst, std::abs(a[0] - b[0]), std::abs(a[1] - b[1])});
  }
  // both integrate the same smooth motion with RK4 at dt = 1e-3 and project to 1e-10
  EXPECT_LT(worst, 1e-8);
  EXPECT_GT(std::abs(plain.sample().probe_values[2]), 0.1);  // it moved
}

TEST(Determinacy, MasslessFreeBodyIsRejectedByName) {
  SceneDef scene = test::empty_scene("rk4", 1e-3, CorrectionDef::Method::kBaumgarte);
  scene.bodies.push_back(test::body("ghost", 0.0, 0.0, Vec2(1.0, 1.0)));
  try {
    Simulation sim(scene);
    FAIL() << "a massless free body was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ghost"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("undetermined"), std::string::npos) << e.what();
  }
}

TEST(Determinacy, MasslessBodyOnOnePinIsRejectedByName) {
  // the pin fixes the point, not the rotation about it
  SceneDef scene = test::empty_scene("rk4", 1e-3, CorrectionDef::Method::kBaumgarte);
  scene.bodies.push_back(test::body("flag", 0.0, 0.0, Vec2(0.5, 0.0)));
  scene.joints.push_back(test::revolute("pin", "ground", "flag", Vec2::Zero(), Vec2(-0.5, 0.0)));
  try {
    Simulation sim(scene);
    FAIL() << "a massless body on one pin was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flag"), std::string::npos) << e.what();
  }
}

TEST(Determinacy, MasslessBodyWeldedToAMassiveOneIsAccepted) {
  SceneDef scene = test::empty_scene("rk4", 1e-3, CorrectionDef::Method::kBaumgarte);
  scene.bodies.push_back(test::body("heavy", 1.0, 0.1, Vec2(0.0, 0.0)));
  scene.bodies.push_back(test::body("virtual", 0.0, 0.0, Vec2(0.5, 0.0)));
  scene.bodies.back().is_virtual = true;
  JointDef weld = test::revolute("weld", "heavy", "virtual", Vec2(0.5, 0.0), Vec2::Zero());
  weld.kind = JointDef::Kind::kRigid;
  scene.joints.push_back(weld);
  Simulation sim(scene);
  EXPECT_EQ(sim.info().virtual_bodies, 1);
  sim.initialize();
  sim.advance_to(1.0);
  // the pair falls freely: y = -g t^2 / 2 (RK4 is exact on a quadratic)
  Snapshot snap;
  sim.fill_snapshot(snap);
  EXPECT_NEAR(snap.bodies[2].y, -0.5 * 9.81, 1e-9);
  EXPECT_NEAR(snap.bodies[2].x, 0.5, 1e-9);
}

TEST(Modules, UnconstrainedSceneRunsWithoutConstraintSolver) {
  SceneDef scene = test::empty_scene("rk4", 1e-2, CorrectionDef::Method::kBaumgarte);
  scene.bodies.push_back(test::body("stone", 2.0, 0.1, Vec2(0.0, 10.0)));
  scene.bodies[0].velocity = Vec2(1.0, 2.0);
  Simulation sim(scene);
  const auto& modules = sim.info().active_modules;
  EXPECT_FALSE(has(modules, "constraint_solver"));
  EXPECT_FALSE(has(modules, "pd_forces"));
  EXPECT_TRUE(has(modules, "rigid_bodies"));
  EXPECT_TRUE(has(modules, "gravity"));
  sim.initialize();
  sim.advance_to(1.0);
  Snapshot snap;
  sim.fill_snapshot(snap);
  // ballistic flight; RK4 integrates the quadratic exactly
  EXPECT_NEAR(snap.bodies[1].x, 1.0, 1e-12);
  EXPECT_NEAR(snap.bodies[1].y, 10.0 + 2.0 - 0.5 * 9.81, 1e-12);
  EXPECT_NEAR(sim.time(), 1.0, 0.0);
}

TEST(Modules, ConstrainedSceneListsConstraintSolverAndForceElements) {
  SceneDef scene = test::point_pendulum(1.0, 0.5, "rk4", 1e-3);
  ForceDef spring;
  spring.kind = ForceDef::Kind::kSpringDamper;
  spring.name = "spring";
  spring.body_i = "ground";
  spring.body_j = "bob";
  spring.point_i = Vec2(1.0, 0.0);
  spring.stiffness = 10.0;
  scene.forces.push_back(spring);
  Simulation sim(scene);
  EXPECT_TRUE(has(sim.info().active_modules, "constraint_solver"));
  EXPECT_TRUE(has(sim.info().active_modules, "force_elements"));
  EXPECT_EQ(sim.info().force_elements, 1);
}

}  // namespace
}  // namespace periflex
