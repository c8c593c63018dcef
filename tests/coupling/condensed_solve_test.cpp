// Rigid-flexible joints solved by elimination give the same accelerations, multipliers and
// projections as the full augmented system they replace, on the shipped coupled scenes, in a
// state off the constraint manifold (so the Baumgarte and projection terms are exercised).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

#include "coupled_run.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"

namespace periflex {
namespace {

struct Solved {
  Eigen::VectorXd qdd, lambda, q_projected, qd_projected;
  int reduced_coordinates = 0, reduced_rows = 0;
};

Solved solve(SystemModel& model, bool condense, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  Dynamics dynamics(model);
  CorrectionDef baumgarte;
  baumgarte.method = CorrectionDef::Method::kBaumgarte;
  baumgarte.alpha = baumgarte.beta = 50.0;
  dynamics.set_correction(baumgarte);
  dynamics.set_condense_attachments(condense);
  dynamics.analyse(0.0);
  Solved s;
  Eigen::Vector3d power;
  dynamics.derivative(0.0, q, qd, s.qdd, power);
  s.lambda = dynamics.multipliers();
  s.q_projected = q;
  dynamics.project_positions(0.0, s.q_projected, 1e-14, 5);
  s.qd_projected = qd;
  dynamics.project_velocities(0.0, s.q_projected, s.qd_projected);
  s.reduced_coordinates = dynamics.reduced_coordinates();
  s.reduced_rows = dynamics.reduced_rows();
  return s;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

// Solves the scene's model both ways in a jittered state and compares.
void expect_condensed_matches_full(const SceneDef& scene, double jitter = 1e-3) {
  std::unique_ptr<SystemModel> model = build_system_model(scene);

  // every coordinate jittered: particles by 1e-3 of the model size (gripped ones too, so the
  // joints are violated), body angles by 1e-3 rad; velocities random
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd q = model->q0, qd(q.size());
  for (int c = 0; c < q.size(); ++c) {
    q[c] += jitter * unit(rng) * (c < model->rigid_coordinates && c % 3 == 2 ? 1.0 : model->length_scale);
    qd[c] = 0.1 * unit(rng);
  }

  const Solved full = solve(*model, false, q, qd);
  const Solved condensed = solve(*model, true, q, qd);
  // the elimination must actually have happened: fewer unknowns in the matrix
  EXPECT_LT(condensed.reduced_coordinates, full.reduced_coordinates);
  EXPECT_LT(condensed.reduced_rows, full.reduced_rows);

  // same linear algebra, different elimination order: agreement to 1e-9 of the largest entry
  // (the sparse LU of the full system pivots on numbers spanning many orders of magnitude)
  EXPECT_LT(relative_difference(condensed.qdd, full.qdd), 1e-9);
  EXPECT_LT(relative_difference(condensed.lambda, full.lambda), 1e-9);
  EXPECT_LT(relative_difference(condensed.q_projected - q, full.q_projected - q), 1e-9);
  EXPECT_LT(relative_difference(condensed.qd_projected - qd, full.qd_projected - qd), 1e-9);
}

class CondensedSolve : public testing::TestWithParam<const char*> {};

TEST_P(CondensedSolve, MatchesTheFullAugmentedSystem) {
  expect_condensed_matches_full(load_scene(test::scene_path(GetParam())));
}

// Joints eliminated in part: the plate held whole by two grips (most of the second joint's
// rows left out as dependent, a few kept to tie the grips, their particles in the matrix), on
// a coarse grid; and the flexible double four-bar started singular (two pins left out).
TEST(CondensedSolve, JointsEliminatedInPartMatchTheFullAugmentedSystem) {
  SceneDef plate = load_scene(std::string(PERIFLEX_TEST_DATA) + "/scenes/plate_held_whole.toml");
  plate.flex_bodies.front().grid_spacing = 4e-3;
  {
    SCOPED_TRACE("plate_held_whole");
    expect_condensed_matches_full(plate);
  }
  // jittered by 1e-2: within 1e-3 of its singular position the system is too ill-conditioned
  // for two elimination orders to agree to 1e-9 (they do from 1e-2 on)
  SCOPED_TRACE("a02_singular_start_flexible");
  expect_condensed_matches_full(load_scene(std::string(PERIFLEX_TEST_DATA) + "/scenes/a02_singular_start_flexible.toml"), 1e-2);
}

INSTANTIATE_TEST_SUITE_P(CoupledScenes, CondensedSolve,
                         testing::Values("flexible_pendulum", "notched_plate", "flexible_slider_crank",
                                         "flexible_four_bar"));

}  // namespace
}  // namespace periflex
