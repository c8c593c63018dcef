#include "mbs/applied_force.h"

namespace periflex {

AppliedForce::AppliedForce(std::string name, BodyPoint point, const Vec2& direction, TimeFunction magnitude)
    : name_(std::move(name)), point_(point), direction_(direction), magnitude_(std::move(magnitude)) {}

void AppliedForce::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd&, double t, Eigen::VectorXd& g) {
  point_.add_force(g, magnitude_(t) * direction_, 1.0, q);
}

double AppliedForce::external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const {
  return (magnitude_(t) * direction_).dot(point_.velocity(q, qd));
}

// the moment of a fixed-direction force about the body origin turns with the body
bool AppliedForce::add_coupling(const Eigen::VectorXd&, SparsityPattern& pattern) const {
  pattern.add_block(point_.coordinates(), point_.coordinates());
  return true;
}

}  // namespace periflex
