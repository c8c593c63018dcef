// Revolute-revolute joint (massless link of length L between P_i and P_j):
//   Phi = (d.d - L^2) / (2 L) = 0,  d = P_j - P_i   (1 equation, in units of length).
#pragma once

#include <string>

#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class RevoluteRevoluteJoint : public Constraint {
 public:
  // length > 0.
  RevoluteRevoluteJoint(std::string name, BodyPoint p_i, BodyPoint p_j, double length);
  const std::string& name() const override { return name_; }
  int rows() const override { return 1; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  const BodyPoint& point_i() const { return p_i_; }
  const BodyPoint& point_j() const { return p_j_; }
  double length() const { return length_; }

 private:
  std::string name_;
  BodyPoint p_i_, p_j_;
  double length_;
};

}  // namespace periflex
