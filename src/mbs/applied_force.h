// A force f(t) * direction (global direction) applied at a body-fixed point. Its power
// F . v_P is external work.
#pragma once

#include <string>

#include "core/time_function.h"
#include "mbs/body_point.h"
#include "mbs/force_element.h"

namespace periflex {

class AppliedForce : public ForceElement {
 public:
  AppliedForce(std::string name, BodyPoint point, const Vec2& direction, TimeFunction magnitude);
  const std::string& name() const override { return name_; }
  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const override;
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;
  const BodyPoint& point() const { return point_; }

 private:
  std::string name_;
  BodyPoint point_;
  Vec2 direction_;
  TimeFunction magnitude_;
};

}  // namespace periflex
