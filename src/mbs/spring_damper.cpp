#include "mbs/spring_damper.h"

namespace periflex {

SpringDamper::SpringDamper(std::string name, BodyPoint p_i, BodyPoint p_j, double stiffness, double damping,
                           double free_length, TimeFunction actuator)
    : name_(std::move(name)),
      p_i_(p_i),
      p_j_(p_j),
      stiffness_(stiffness),
      damping_(damping),
      free_length_(free_length),
      actuator_(std::move(actuator)) {}

void SpringDamper::kinematics(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, double& length, double& rate,
                              Vec2& e) const {
  const Vec2 d = p_j_.position(q) - p_i_.position(q);
  length = d.norm();
  // coincident points have no direction: no force, no rate
  e = length > 0.0 ? Vec2(d / length) : Vec2::Zero();
  rate = qd ? e.dot(p_j_.velocity(q, *qd) - p_i_.velocity(q, *qd)) : 0.0;
}

void SpringDamper::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) {
  double length, rate;
  Vec2 e;
  kinematics(q, &qd, length, rate, e);
  const double tension = stiffness_ * (length - free_length_) + damping_ * rate + actuator_(t);
  // tension pulls P_j towards P_i and P_i towards P_j
  p_i_.add_force(g, tension * e, 1.0, q);
  p_j_.add_force(g, tension * e, -1.0, q);
}

double SpringDamper::potential_energy(const Eigen::VectorXd& q) const {
  double length, rate;
  Vec2 e;
  kinematics(q, nullptr, length, rate, e);
  const double stretch = length - free_length_;
  return 0.5 * stiffness_ * stretch * stretch;
}

double SpringDamper::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  double length, rate;
  Vec2 e;
  kinematics(q, &qd, length, rate, e);
  return damping_ * rate * rate;
}

double SpringDamper::external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const {
  double length, rate;
  Vec2 e;
  kinematics(q, &qd, length, rate, e);
  return -actuator_(t) * rate;
}

// the force between the two points moves with all six coordinates of their bodies
bool SpringDamper::add_coupling(const Eigen::VectorXd&, SparsityPattern& pattern) const {
  std::vector<int> coordinates = p_i_.coordinates();
  const std::vector<int> other = p_j_.coordinates();
  coordinates.insert(coordinates.end(), other.begin(), other.end());
  pattern.add_block(coordinates, coordinates);
  return true;
}

}  // namespace periflex
