// Translational spring-damper-actuator between P_i and P_j. With L = |P_j - P_i| and
// e = (P_j - P_i) / L, the tension T = k (L - L0) + c L_dot + a(t) pulls the points together.
//   potential k (L - L0)^2 / 2,  dissipation c L_dot^2,  actuator power -a(t) L_dot.
#pragma once

#include <string>

#include "core/time_function.h"
#include "mbs/body_point.h"
#include "mbs/force_element.h"

namespace periflex {

class SpringDamper : public ForceElement {
 public:
  SpringDamper(std::string name, BodyPoint p_i, BodyPoint p_j, double stiffness, double damping,
               double free_length, TimeFunction actuator);
  const std::string& name() const override { return name_; }
  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const override;
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;
  const BodyPoint& point_i() const { return p_i_; }
  const BodyPoint& point_j() const { return p_j_; }

 private:
  // Length and its rate; the unit vector e (zero when the points coincide).
  void kinematics(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, double& length, double& rate,
                  Vec2& e) const;
  std::string name_;
  BodyPoint p_i_, p_j_;
  double stiffness_, damping_, free_length_;
  TimeFunction actuator_;
};

}  // namespace periflex
