// Rotational spring-damper between two bodies (either may be the ground): with
// theta = phi_j - phi_i, the torque k (theta - theta0) + c theta_dot acts on j negatively and
// on i positively. Potential k (theta - theta0)^2 / 2, dissipation c theta_dot^2.
#pragma once

#include <string>

#include "mbs/force_element.h"

namespace periflex {

class RotationalSpring : public ForceElement {
 public:
  RotationalSpring(std::string name, int body_i, int body_j, double stiffness, double damping, double free_angle);
  const std::string& name() const override { return name_; }
  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;
  int body_i() const { return body_i_; }
  int body_j() const { return body_j_; }

 private:
  double relative(const Eigen::VectorXd& v) const;  // v_j - v_i of the angle entries
  std::string name_;
  int body_i_, body_j_;
  double stiffness_, damping_, free_angle_;
};

}  // namespace periflex
