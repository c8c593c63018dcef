// A torque f(t) on a body. Its power f(t) phi_dot is external work.
#pragma once

#include <string>

#include "core/time_function.h"
#include "mbs/force_element.h"

namespace periflex {

class AppliedTorque : public ForceElement {
 public:
  AppliedTorque(std::string name, int body, TimeFunction magnitude);
  const std::string& name() const override { return name_; }
  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const override;
  // constant in q and qd: no coupling
  bool add_coupling(const Eigen::VectorXd&, SparsityPattern&) const override { return true; }
  int body() const { return body_; }

 private:
  std::string name_;
  int body_;
  TimeFunction magnitude_;
};

}  // namespace periflex
