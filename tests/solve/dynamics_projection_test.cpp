// Projections of Dynamics onto the constraints (solve/dynamics_projection.cpp): a perturbed state
// brought back onto the joints, a state already on them left alone, velocities made consistent.
#include <gtest/gtest.h>

#include <random>

#include "model/system_model.h"
#include "solve/dynamics.h"
#include "test_scenes.h"

namespace periflex {
namespace {

Eigen::VectorXd noise(int size, unsigned seed, double scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(size);
  for (int k = 0; k < size; ++k) v[k] = u(rng);
  return v;
}

struct Pendulum {
  std::unique_ptr<SystemModel> model =
      build_system_model(test::double_pendulum("verlet", 1e-3, CorrectionDef::Method::kProjection));
  Dynamics dynamics{*model};
  Pendulum() { dynamics.analyse(0.0); }
};

TEST(DynamicsProjection, PositionsPerturbedComeBackOntoTheJoints) {
  Pendulum p;
  Eigen::VectorXd q = p.model->q0 + noise(p.model->coordinate_count, 1, 1e-3);
  ASSERT_GT(p.dynamics.position_violation(0.0, q), 1e-4);
  const double left = p.dynamics.project_positions(0.0, q, 1e-13, 20);
  EXPECT_LE(left, 1e-13);
  EXPECT_LE(p.dynamics.position_violation(0.0, q), 1e-13);
  // the least change: no farther from the start than the perturbation itself
  EXPECT_LT((q - p.model->q0).norm(), 2e-3 * std::sqrt(6.0));
}

TEST(DynamicsProjection, PositionsOnTheJointsStayWhereTheyAre) {
  Pendulum p;
  Eigen::VectorXd q = p.model->q0;
  ASSERT_LE(p.dynamics.position_violation(0.0, q), 1e-15);
  p.dynamics.project_positions(0.0, q, 1e-13, 20);
  EXPECT_EQ(q, p.model->q0);
}

TEST(DynamicsProjection, ShakeFromTheStepStartAlsoSatisfiesTheJoints) {
  Pendulum p;
  const Eigen::VectorXd start = p.model->q0;
  Eigen::VectorXd q = start + noise(p.model->coordinate_count, 2, 1e-3);
  const double left = p.dynamics.project_positions_from(0.0, start, q, 1e-13, 20);
  EXPECT_LE(left, 1e-13);
  EXPECT_LE(p.dynamics.position_violation(0.0, q), 1e-13);
}

TEST(DynamicsProjection, VelocitiesMadeConsistentWithTheJoints) {
  Pendulum p;
  const Eigen::VectorXd& q = p.model->q0;
  Eigen::VectorXd qd = noise(p.model->coordinate_count, 3, 1.0);
  ASSERT_GT(p.dynamics.velocity_violation(0.0, q, qd), 1e-2);
  const double change = p.dynamics.project_velocities(0.0, q, qd);
  EXPECT_GT(change, 0.0);
  EXPECT_LE(p.dynamics.velocity_violation(0.0, q, qd), 1e-12);
  // projecting again changes nothing more than round-off
  EXPECT_LE(p.dynamics.project_velocities(0.0, q, qd), 1e-12);
}

}  // namespace
}  // namespace periflex
