#include "mbs/rotational_spring.h"

namespace periflex {

RotationalSpring::RotationalSpring(std::string name, int body_i, int body_j, double stiffness, double damping,
                                   double free_angle)
    : name_(std::move(name)),
      body_i_(body_i),
      body_j_(body_j),
      stiffness_(stiffness),
      damping_(damping),
      free_angle_(free_angle) {}

double RotationalSpring::relative(const Eigen::VectorXd& v) const {
  const double a_j = body_j_ < 0 ? 0.0 : v[3 * body_j_ + 2];
  const double a_i = body_i_ < 0 ? 0.0 : v[3 * body_i_ + 2];
  return a_j - a_i;
}

void RotationalSpring::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, Eigen::VectorXd& g) {
  const double torque = stiffness_ * (relative(q) - free_angle_) + damping_ * relative(qd);
  if (body_j_ >= 0) g[3 * body_j_ + 2] -= torque;
  if (body_i_ >= 0) g[3 * body_i_ + 2] += torque;
}

double RotationalSpring::potential_energy(const Eigen::VectorXd& q) const {
  const double twist = relative(q) - free_angle_;
  return 0.5 * stiffness_ * twist * twist;
}

double RotationalSpring::dissipation_power(const Eigen::VectorXd&, const Eigen::VectorXd& qd) const {
  const double rate = relative(qd);
  return damping_ * rate * rate;
}

// the torque moves with the two angles and their rates
bool RotationalSpring::add_coupling(const Eigen::VectorXd&, SparsityPattern& pattern) const {
  const std::vector<int> angles = {body_i_ < 0 ? -1 : 3 * body_i_ + 2, body_j_ < 0 ? -1 : 3 * body_j_ + 2};
  pattern.add_block(angles, angles);
  return true;
}

}  // namespace periflex
