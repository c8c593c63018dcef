// Revolute-translational joint: the pin P_j (on body j) slides along the line through P_i in
// the body-fixed direction u'_i of body i, at a signed distance `offset` to the left of it:
//   n_i . (P_j - P_i) - offset = 0,  n_i = A_i perp(u'_i)   (1 equation).
#pragma once

#include <string>

#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class RevoluteTranslationalJoint : public Constraint {
 public:
  RevoluteTranslationalJoint(std::string name, BodyPoint p_i, BodyPoint p_j, const Vec2& axis_i, double offset);
  const std::string& name() const override { return name_; }
  int rows() const override { return 1; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  const AxisGap& normal_gap() const { return gap_; }

 private:
  std::string name_;
  AxisGap gap_;
  double offset_;
};

}  // namespace periflex
