// Revolute (pin) joint: P_i and P_j coincide, r_i + A_i s'_i - r_j - A_j s'_j = 0 (2 equations).
#pragma once

#include <string>

#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class RevoluteJoint : public Constraint {
 public:
  RevoluteJoint(std::string name, BodyPoint p_i, BodyPoint p_j);
  const std::string& name() const override { return name_; }
  int rows() const override { return 2; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  // The joint's two points, for drawing.
  const BodyPoint& point_i() const { return p_i_; }
  const BodyPoint& point_j() const { return p_j_; }

 private:
  std::string name_;
  BodyPoint p_i_, p_j_;
};

// Appends x, y, phi of each non-ground body to out.
void append_body_coordinates(int body, std::vector<int>& out);

}  // namespace periflex
