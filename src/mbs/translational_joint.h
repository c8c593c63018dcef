// Translational (prismatic) joint: P_j stays on the line through P_i along the body-fixed axis
// u'_i, and the bodies do not rotate relative to each other (2 equations):
//   n_i . (P_j - P_i) = 0,  n_i = A_i perp(u'_i);   phi_j - phi_i - theta0 = 0.
#pragma once

#include <string>

#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class TranslationalJoint : public Constraint {
 public:
  // axis_i: sliding direction, body-fixed in body i (normalised here).
  TranslationalJoint(std::string name, BodyPoint p_i, BodyPoint p_j, const Vec2& axis_i, double relative_angle);
  const std::string& name() const override { return name_; }
  int rows() const override { return 2; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  const AxisGap& normal_gap() const { return gap_; }

 private:
  std::string name_;
  AxisGap gap_;   // normal distance of P_j from the axis line
  double relative_angle_;
};

}  // namespace periflex
