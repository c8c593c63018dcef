// Force elements: conservative forces equal -dV/dq (central differences of the potential
// alone), damping forces dissipate exactly the reported power, and actuators / applied loads
// feed in exactly the reported external power Q . qd.
#include <gtest/gtest.h>

#include <random>

#include "mbs/force_factory.h"
#include "mbs/three_body_coordinates.h"

namespace periflex {
namespace {

using testing::kSpreadPose;
using testing::kThreeBodyCoordinates;
using testing::random_coordinates;

Eigen::VectorXd forces(ForceElement& f, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(kThreeBodyCoordinates);
  f.add_forces(q, qd, t, g);
  return g;
}

ForceDef spring(double k, double c, double actuator) {
  ForceDef def;
  def.kind = ForceDef::Kind::kSpringDamper;
  def.name = std::string("s");  // a bare literal here trips a false -Wrestrict warning
  def.point_i = Vec2(0.2, -0.1);
  def.point_j = Vec2(-0.3, 0.4);
  def.stiffness = k;
  def.damping = c;
  def.free_length = 0.5;
  def.actuator = TimeFunction::linear(actuator, 2.0);
  return def;
}

ForceDef rotational(double k, double c) {
  ForceDef def;
  def.kind = ForceDef::Kind::kRotationalSpring;
  def.name = std::string("r");  // a bare literal here trips a false -Wrestrict warning
  def.stiffness = k;
  def.damping = c;
  def.free_angle = 0.3;
  def.free_angle_from_initial = false;
  return def;
}

// -dV/dq by central differences: step 1e-6, V = O(10) -> error ~1e-9 from round-off
void check_conservative(ForceElement& f) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_coordinates(rng, 2.0);
    const Eigen::VectorXd qd = random_coordinates(rng, 1.0);
    const Eigen::VectorXd g = forces(f, q, qd, 0.0);
    const double h = 1e-6;
    for (int k = 0; k < kThreeBodyCoordinates; ++k) {
      Eigen::VectorXd qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      const double dv = (f.potential_energy(qp) - f.potential_energy(qm)) / (2 * h);
      EXPECT_NEAR(g[k], -dv, 1e-6 * (1 + std::abs(g[k]))) << f.name() << " coordinate " << k;
    }
  }
}

// damping-only element: power of its forces is minus the reported dissipation (round-off only)
void check_dissipative(ForceElement& f) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_coordinates(rng, 2.0);
    const Eigen::VectorXd qd = random_coordinates(rng, 1.0);
    const double power = forces(f, q, qd, 0.0).dot(qd);
    EXPECT_NEAR(power, -f.dissipation_power(q, qd), 1e-12 * (1 + std::abs(power))) << f.name();
    EXPECT_GE(f.dissipation_power(q, qd), 0.0);
  }
}

// loads and actuators: power of the forces equals the reported external power
void check_external(ForceElement& f) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_coordinates(rng, 2.0);
    const Eigen::VectorXd qd = random_coordinates(rng, 1.0);
    const double t = 0.1 * trial;
    const double power = forces(f, q, qd, t).dot(qd);
    EXPECT_NEAR(power, f.external_power(q, qd, t), 1e-12 * (1 + std::abs(power))) << f.name();
  }
}

TEST(ForceElements, SpringForceIsMinusPotentialGradient) {
  for (auto [i, j] : {std::pair{0, 2}, std::pair{-1, 1}, std::pair{1, -1}}) {
    auto f = make_force_element(spring(120.0, 0.0, 0.0), i, j, kSpreadPose);
    check_conservative(*f);
  }
}

TEST(ForceElements, DamperDissipatesReportedPower) {
  auto f = make_force_element(spring(0.0, 3.5, 0.0), 0, 2, kSpreadPose);
  check_dissipative(*f);
  auto r = make_force_element(rotational(0.0, 2.0), 1, 0, kSpreadPose);
  check_dissipative(*r);
}

TEST(ForceElements, ActuatorFeedsReportedPower) {
  auto f = make_force_element(spring(0.0, 0.0, 4.0), 0, 1, kSpreadPose);
  check_external(*f);
}

TEST(ForceElements, RotationalSpringForceIsMinusPotentialGradient) {
  for (auto [i, j] : {std::pair{0, 2}, std::pair{-1, 1}, std::pair{1, -1}}) {
    auto f = make_force_element(rotational(50.0, 0.0), i, j, kSpreadPose);
    check_conservative(*f);
  }
}

TEST(ForceElements, AppliedForceAndTorqueFeedReportedPower) {
  ForceDef force;
  force.kind = ForceDef::Kind::kForce;
  force.name = "push";
  force.point_i = Vec2(0.4, -0.2);
  force.direction = Vec2(0.3, -1.0);
  force.magnitude = TimeFunction::linear(2.0, -1.0);
  auto f = make_force_element(force, 1, -1, kSpreadPose);
  check_external(*f);

  // the moment about the body origin is s x F
  const Eigen::VectorXd q = kSpreadPose, qd = Eigen::VectorXd::Zero(kThreeBodyCoordinates);
  const Eigen::VectorXd g = forces(*f, q, qd, 0.0);
  const Vec2 arm = rotation(q[5]) * force.point_i;
  EXPECT_NEAR(g[5], cross(arm, 2.0 * force.direction), 1e-14);

  ForceDef torque;
  torque.kind = ForceDef::Kind::kTorque;
  torque.name = "twist";
  torque.magnitude = TimeFunction::constant(3.0);
  auto m = make_force_element(torque, 2, -1, kSpreadPose);
  check_external(*m);
  EXPECT_EQ(forces(*m, q, qd, 0.0)[8], 3.0);
}

TEST(ForceElements, FreeLengthFromInitialConfigurationGivesZeroForce) {
  ForceDef def = spring(100.0, 0.0, 0.0);
  def.free_length = -1.0;
  auto f = make_force_element(def, 0, 1, kSpreadPose);
  EXPECT_NEAR(f->potential_energy(kSpreadPose), 0.0, 1e-20);
  EXPECT_NEAR(forces(*f, kSpreadPose, Eigen::VectorXd::Zero(kThreeBodyCoordinates), 0.0).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace periflex
