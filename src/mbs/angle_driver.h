// Angle driver (rheonomic): phi_plus - phi_minus - f(t) = 0 (1 equation).
// Absolute angle: plus = body i, minus = ground. Relative angle: plus = body j, minus = body i.
#pragma once

#include <string>

#include "core/time_function.h"
#include "mbs/constraint.h"

namespace periflex {

class AngleDriver : public Constraint {
 public:
  // plus_body / minus_body: rigid body indices, -1 for the ground.
  AngleDriver(std::string name, int plus_body, int minus_body, TimeFunction f);
  const std::string& name() const override { return name_; }
  int rows() const override { return 1; }
  bool is_driver() const override { return true; }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void time_derivative(const Eigen::VectorXd& q, double t, double* phi_t) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;
  int plus_body() const { return plus_; }
  int minus_body() const { return minus_; }

 private:
  std::string name_;
  int plus_, minus_;
  TimeFunction f_;
};

}  // namespace periflex
