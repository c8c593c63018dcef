#include "mbs/applied_torque.h"

namespace periflex {

AppliedTorque::AppliedTorque(std::string name, int body, TimeFunction magnitude)
    : name_(std::move(name)), body_(body), magnitude_(std::move(magnitude)) {}

void AppliedTorque::add_forces(const Eigen::VectorXd&, const Eigen::VectorXd&, double t, Eigen::VectorXd& g) {
  if (body_ >= 0) g[3 * body_ + 2] += magnitude_(t);
}

double AppliedTorque::external_power(const Eigen::VectorXd&, const Eigen::VectorXd& qd, double t) const {
  return body_ < 0 ? 0.0 : magnitude_(t) * qd[3 * body_ + 2];
}

}  // namespace periflex
