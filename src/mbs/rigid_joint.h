// Rigid (weld) joint: a revolute joint at P_i = P_j plus a fixed relative angle,
// phi_j - phi_i - theta0 = 0 (3 equations).
#pragma once

#include <string>

#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class RigidJoint : public Constraint {
 public:
  RigidJoint(std::string name, BodyPoint p_i, BodyPoint p_j, double relative_angle);
  const std::string& name() const override { return name_; }
  int rows() const override { return 3; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  const BodyPoint& point_i() const { return p_i_; }
  const BodyPoint& point_j() const { return p_j_; }

 private:
  std::string name_;
  BodyPoint p_i_, p_j_;
  double relative_angle_;
};

}  // namespace periflex
