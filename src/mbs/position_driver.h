// Position driver (rheonomic): (A_a e') . (P_b - P_a) - f(t) = 0 (1 equation).
// Absolute position: a = the global origin (ground), e' a global axis, b = P_i.
// Relative position: a = P_i with e' body-fixed in body i, b = P_j.
#pragma once

#include <string>

#include "core/time_function.h"
#include "mbs/body_point.h"
#include "mbs/constraint.h"

namespace periflex {

class PositionDriver : public Constraint {
 public:
  // gap.axis is normalised here.
  PositionDriver(std::string name, AxisGap gap, TimeFunction f);
  const std::string& name() const override { return name_; }
  int rows() const override { return 1; }
  bool is_driver() const override { return true; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void time_derivative(const Eigen::VectorXd& q, double t, double* phi_t) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  const AxisGap& gap() const { return gap_; }

 private:
  std::string name_;
  AxisGap gap_;
  TimeFunction f_;
};

}  // namespace periflex
