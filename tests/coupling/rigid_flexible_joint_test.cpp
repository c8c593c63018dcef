// The rigid-flexible joint on its own: residual zero at set-up, Jacobian and gamma against
// central finite differences, clamp to ground, reaction resultant, and bad input.
#include "coupling/rigid_flexible_joint.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <random>

#include "core/error.h"

namespace periflex {
namespace {

// two rigid bodies (6 coordinates) then five particles (10 coordinates)
constexpr int kBodies = 2;
constexpr int kParticles = 5;
constexpr int kSize = 3 * kBodies + 2 * kParticles;

Eigen::VectorXd random_vector(int n, unsigned seed, double scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

std::vector<int> particle_coordinates() {
  // attach particles 0, 2, 3, 4 (not all, to check that the others stay untouched)
  return {3 * kBodies + 0, 3 * kBodies + 4, 3 * kBodies + 6, 3 * kBodies + 8};
}

Eigen::MatrixXd dense_jacobian(const Constraint& c, const Eigen::VectorXd& q) {
  Triplets triplets;
  c.jacobian(q, 0.0, 0, triplets);
  Eigen::SparseMatrix<double> j(c.rows(), q.size());
  j.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::MatrixXd(j);
}

Eigen::VectorXd residual(const Constraint& c, const Eigen::VectorXd& q) {
  Eigen::VectorXd phi(c.rows());
  c.residual(q, 0.0, phi.data());
  return phi;
}

TEST(RigidFlexibleJoint, ResidualIsExactlyZeroAtSetUp) {
  for (int body : {-1, 0, 1}) {
    const Eigen::VectorXd q0 = random_vector(kSize, 7 + body, 2.0);
    const auto joint = make_rigid_flexible_joint("grip", body, particle_coordinates(), q0);
    ASSERT_EQ(joint->rows(), 8);
    // rounding of one rotation and back: a few ulps of the coordinate size (|q| <= 2 + 2*2)
    EXPECT_LT(residual(*joint, q0).cwiseAbs().maxCoeff(), 1e-14) << "body " << body;
  }
}

TEST(RigidFlexibleJoint, JacobianMatchesCentralDifferences) {
  const Eigen::VectorXd q0 = random_vector(kSize, 11, 1.0);
  const auto joint = make_rigid_flexible_joint("grip", 1, particle_coordinates(), q0);
  // evaluate away from the set-up configuration
  const Eigen::VectorXd q = q0 + random_vector(kSize, 12, 0.3);
  const Eigen::MatrixXd analytic = dense_jacobian(*joint, q);
  const double h = 1e-6;
  Eigen::MatrixXd numeric(joint->rows(), kSize);
  for (int j = 0; j < kSize; ++j) {
    Eigen::VectorXd qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    numeric.col(j) = (residual(*joint, qp) - residual(*joint, qm)) / (2 * h);
  }
  // central difference error ~ h^2 |Phi'''| ~ 1e-12, plus rounding ~ eps/h ~ 1e-10
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-8);
  // the unattached particle 1 (coordinates 8, 9) and body 0 must not appear
  EXPECT_EQ(analytic.col(3 * kBodies + 2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(analytic.leftCols(3).cwiseAbs().maxCoeff(), 0.0);
}

TEST(RigidFlexibleJoint, GammaMatchesSecondTimeDerivative) {
  // gamma = -(Phi_q qd)_q qd: the second time derivative of Phi along q(t) = q + t qd
  // with zero acceleration equals -gamma
  const Eigen::VectorXd q0 = random_vector(kSize, 21, 1.0);
  const auto joint = make_rigid_flexible_joint("grip", 0, particle_coordinates(), q0);
  const Eigen::VectorXd q = q0 + random_vector(kSize, 22, 0.3);
  const Eigen::VectorXd qd = random_vector(kSize, 23, 2.0);
  Eigen::VectorXd gamma(joint->rows());
  joint->gamma(q, qd, 0.0, gamma.data());
  const double h = 1e-4;
  const Eigen::VectorXd second =
      (residual(*joint, q + h * qd) - 2 * residual(*joint, q) + residual(*joint, q - h * qd)) / (h * h);
  // truncation ~ h^2 |Phi''''| ~ 1e-8 * 16, rounding ~ eps / h^2 ~ 2e-8
  EXPECT_LT((gamma + second).cwiseAbs().maxCoeff(), 1e-6);
  // and it is not trivially zero
  EXPECT_GT(gamma.cwiseAbs().maxCoeff(), 1e-2);
}

TEST(RigidFlexibleJoint, GroundClampHoldsParticlesWhereTheyStart) {
  const Eigen::VectorXd q0 = random_vector(kSize, 31, 1.0);
  const auto joint = make_rigid_flexible_joint("clamp", -1, particle_coordinates(), q0);
  Eigen::VectorXd q = q0;
  q[3 * kBodies + 4] += 0.25;  // move particle 2 in x
  const Eigen::VectorXd phi = residual(*joint, q);
  EXPECT_DOUBLE_EQ(phi[2], -0.25);
  EXPECT_EQ(phi.cwiseAbs().sum(), 0.25);
  // only -I on the particles
  const Eigen::MatrixXd jac = dense_jacobian(*joint, q);
  EXPECT_EQ(jac.leftCols(3 * kBodies).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(jac.sum(), -8.0);
  Eigen::VectorXd gamma(joint->rows());
  joint->gamma(q, random_vector(kSize, 32, 1.0), 0.0, gamma.data());
  EXPECT_EQ(gamma.cwiseAbs().maxCoeff(), 0.0);
}

TEST(RigidFlexibleJoint, ParticlesFollowARigidMotionOfTheBody) {
  // move the body rigidly and place the particles where the body carries them: Phi = 0
  const Eigen::VectorXd q0 = random_vector(kSize, 41, 1.0);
  const auto joint = make_rigid_flexible_joint("grip", 1, particle_coordinates(), q0);
  Eigen::VectorXd q = q0;
  const double turn = 0.7;
  const Vec2 shift(0.3, -0.2);
  const Vec2 r0(q0[3], q0[4]);
  q[3] += shift.x();
  q[4] += shift.y();
  q[5] += turn;
  for (int i : particle_coordinates()) {
    const Vec2 x = r0 + shift + rotation(turn) * (Vec2(q0[i], q0[i + 1]) - r0);
    q[i] = x.x();
    q[i + 1] = x.y();
  }
  EXPECT_LT(residual(*joint, q).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(RigidFlexibleJoint, BodyReactionIsMinusJacobianTransposeTimesLambda) {
  const Eigen::VectorXd q0 = random_vector(kSize, 51, 1.0);
  const auto made = make_rigid_flexible_joint("grip", 1, particle_coordinates(), q0);
  const RigidFlexibleJoint& joint = *made;
  const Eigen::VectorXd q = q0 + random_vector(kSize, 52, 0.2);
  const Eigen::VectorXd lambda = random_vector(joint.rows(), 53, 5.0);
  Vec2 force;
  double torque = 0.0;
  joint.body_reaction(q, lambda.data(), force, torque);
  const Eigen::VectorXd generalised = -dense_jacobian(joint, q).transpose() * lambda;
  EXPECT_NEAR(force.x(), generalised[3], 1e-12);
  EXPECT_NEAR(force.y(), generalised[4], 1e-12);
  EXPECT_NEAR(torque, generalised[5], 1e-12);
}

TEST(RigidFlexibleJoint, CoordinatesListBodyAndParticles) {
  const Eigen::VectorXd q0 = random_vector(kSize, 61, 1.0);
  const auto joint = make_rigid_flexible_joint("grip", 1, particle_coordinates(), q0);
  std::vector<int> coords;
  joint->coordinates(coords);
  const std::vector<int> expected = {3, 4, 5, 6, 7, 10, 11, 12, 13, 14, 15};
  EXPECT_EQ(coords, expected);
}

TEST(RigidFlexibleJoint, EmptyRegionIsAnInputError) {
  const Eigen::VectorXd q0 = random_vector(kSize, 71, 1.0);
  EXPECT_THROW(make_rigid_flexible_joint("grip", 0, {}, q0), InputError);
  EXPECT_THROW(make_rigid_flexible_joint("grip", 0, {kSize - 1}, q0), InputError);
  EXPECT_THROW(make_rigid_flexible_joint("grip", 9, {6}, q0), InputError);
}

}  // namespace
}  // namespace periflex
