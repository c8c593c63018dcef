// Every joint and driver of the catalogue: Phi_q, Phi_t and gamma against finite differences of
// the residual Phi alone, at random configurations, velocities and times.
//
// gamma = -(Phi_q qd)_q qd - 2 Phi_qt qd - Phi_tt is minus the second derivative of
// s -> Phi(q + s qd, t + s) at s = 0, so a central second difference of Phi checks it
// independently of the analytic Jacobian.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <random>

#include "mbs/constraint.h"
#include "mbs/joint_factory.h"
#include "mbs/three_body_coordinates.h"

namespace periflex {
namespace {

constexpr int kBodies = 3;
using testing::kSpreadPose;
using testing::kThreeBodyCoordinates;
using testing::random_coordinates;
static_assert(3 * kBodies == kThreeBodyCoordinates);

Eigen::VectorXd residual(const Constraint& c, const Eigen::VectorXd& q, double t) {
  Eigen::VectorXd phi(c.rows());
  c.residual(q, t, phi.data());
  return phi;
}

Eigen::MatrixXd dense_jacobian(const Constraint& c, const Eigen::VectorXd& q, double t) {
  Triplets triplets;
  c.jacobian(q, t, 0, triplets);
  Eigen::SparseMatrix<double> j(c.rows(), kThreeBodyCoordinates);
  j.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::MatrixXd(j);
}

// Runs the three checks at several random states.
void check_derivatives(const Constraint& c) {
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_coordinates(rng, 2.0);
    const Eigen::VectorXd qd = random_coordinates(rng, 1.5);
    const double t = std::uniform_real_distribution<double>(0.0, 2.0)(rng);

    // Jacobian: central differences, step 1e-6 -> truncation ~1e-12, round-off ~1e-10 at O(1) values
    const double h = 1e-6;
    const Eigen::MatrixXd jac = dense_jacobian(c, q, t);
    for (int col = 0; col < kThreeBodyCoordinates; ++col) {
      Eigen::VectorXd qp = q, qm = q;
      qp[col] += h;
      qm[col] -= h;
      const Eigen::VectorXd fd = (residual(c, qp, t) - residual(c, qm, t)) / (2 * h);
      for (int row = 0; row < c.rows(); ++row) {
        EXPECT_NEAR(jac(row, col), fd[row], 1e-7) << c.name() << " row " << row << " col " << col;
      }
    }

    // Phi_t: same step and bound
    Eigen::VectorXd phi_t(c.rows());
    c.time_derivative(q, t, phi_t.data());
    const Eigen::VectorXd fd_t = (residual(c, q, t + h) - residual(c, q, t - h)) / (2 * h);
    for (int row = 0; row < c.rows(); ++row) EXPECT_NEAR(phi_t[row], fd_t[row], 1e-7) << c.name();

    // gamma: second difference along (qd, 1) with step 1e-4 -> truncation ~1e-9, round-off ~1e-8
    const double s = 1e-4;
    Eigen::VectorXd g(c.rows());
    c.gamma(q, qd, t, g.data());
    const Eigen::VectorXd second = (residual(c, q + s * qd, t + s) - 2 * residual(c, q, t) +
                                    residual(c, q - s * qd, t - s)) / (s * s);
    for (int row = 0; row < c.rows(); ++row) {
      EXPECT_NEAR(g[row], -second[row], 1e-5 * (1 + std::abs(g[row]))) << c.name() << " row " << row;
    }

    // the coordinate list covers every column the Jacobian touches
    std::vector<int> coords;
    c.coordinates(coords);
    for (int col = 0; col < kThreeBodyCoordinates; ++col) {
      if (jac.col(col).norm() > 0) {
        EXPECT_NE(std::find(coords.begin(), coords.end(), col), coords.end());
      }
    }
  }
}

JointDef joint(JointDef::Kind kind) {
  JointDef def;
  def.kind = kind;
  def.name = std::string("j");  // a bare literal here trips a false -Wrestrict warning
  def.point_i = Vec2(0.3, -0.2);
  def.point_j = Vec2(-0.4, 0.25);
  def.axis_i = Vec2(0.6, 0.8);
  def.offset = 0.1;
  def.length = 0.7;
  def.length_from_initial = false;
  def.relative_angle = 0.4;
  def.relative_angle_from_initial = false;
  return def;
}

DriverDef driver(DriverDef::Kind kind) {
  DriverDef def;
  def.kind = kind;
  def.name = std::string("d");  // a bare literal here trips a false -Wrestrict warning
  def.point_i = Vec2(0.2, 0.1);
  def.point_j = Vec2(-0.3, 0.5);
  def.axis = Vec2(1.0, 2.0);
  def.function.kind = TimeFunction::Kind::kHarmonic;
  def.function.offset = 0.2;
  def.function.amplitude = 0.5;
  def.function.omega = 3.0;
  def.function.phase = 0.3;
  return def;
}

// body pairs: two moving bodies, and each side on the ground
const std::pair<int, int> kPairs[] = {{0, 2}, {-1, 1}, {1, -1}};

TEST(ConstraintDerivatives, RevoluteMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) check_derivatives(*make_joint(joint(JointDef::Kind::kRevolute), i, j, kSpreadPose));
}

TEST(ConstraintDerivatives, TranslationalMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) check_derivatives(*make_joint(joint(JointDef::Kind::kTranslational), i, j, kSpreadPose));
}

TEST(ConstraintDerivatives, RigidMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) check_derivatives(*make_joint(joint(JointDef::Kind::kRigid), i, j, kSpreadPose));
}

TEST(ConstraintDerivatives, RevoluteRevoluteMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) check_derivatives(*make_joint(joint(JointDef::Kind::kRevoluteRevolute), i, j, kSpreadPose));
}

TEST(ConstraintDerivatives, RevoluteTranslationalMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) {
    check_derivatives(*make_joint(joint(JointDef::Kind::kRevoluteTranslational), i, j, kSpreadPose));
  }
}

TEST(ConstraintDerivatives, AbsoluteAngleDriverMatchesFiniteDifferences) {
  auto c = make_driver(driver(DriverDef::Kind::kAbsoluteAngle), 1, -1, kSpreadPose);
  EXPECT_TRUE(c->is_driver());
  check_derivatives(*c);
}

TEST(ConstraintDerivatives, RelativeAngleDriverMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) check_derivatives(*make_driver(driver(DriverDef::Kind::kRelativeAngle), i, j, kSpreadPose));
}

TEST(ConstraintDerivatives, AbsolutePositionDriverMatchesFiniteDifferences) {
  check_derivatives(*make_driver(driver(DriverDef::Kind::kAbsolutePosition), 2, -1, kSpreadPose));
}

TEST(ConstraintDerivatives, RelativePositionDriverMatchesFiniteDifferences) {
  for (auto [i, j] : kPairs) {
    check_derivatives(*make_driver(driver(DriverDef::Kind::kRelativePosition), i, j, kSpreadPose));
  }
}

TEST(JointFactory, LengthAndAngleFromInitialConfiguration) {
  // the link takes the initial distance of its points; Phi vanishes at q0
  JointDef link = joint(JointDef::Kind::kRevoluteRevolute);
  link.length_from_initial = true;
  auto c = make_joint(link, 0, 1, kSpreadPose);
  EXPECT_NEAR(residual(*c, kSpreadPose, 0.0)[0], 0.0, 1e-14);
  JointDef weld = joint(JointDef::Kind::kRigid);
  weld.relative_angle_from_initial = true;
  auto w = make_joint(weld, 0, 1, kSpreadPose);
  EXPECT_NEAR(residual(*w, kSpreadPose, 0.0)[2], 0.0, 1e-14);
}

TEST(JointFactory, RejectsJointOfABodyToItself) {
  EXPECT_THROW(make_joint(joint(JointDef::Kind::kRevolute), 1, 1, kSpreadPose), InputError);
  JointDef link = joint(JointDef::Kind::kRevoluteRevolute);
  link.length_from_initial = true;
  link.point_i = link.point_j = Vec2::Zero();
  // both points at the same global place: zero length link
  EXPECT_THROW(make_joint(link, -1, -1, kSpreadPose), InputError);
}

}  // namespace
}  // namespace periflex
