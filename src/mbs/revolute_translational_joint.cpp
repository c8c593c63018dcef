#include "mbs/revolute_translational_joint.h"

#include "mbs/revolute_joint.h"

namespace periflex {

RevoluteTranslationalJoint::RevoluteTranslationalJoint(std::string name, BodyPoint p_i, BodyPoint p_j,
                                                       const Vec2& axis_i, double offset)
    : name_(std::move(name)), gap_{p_i, p_j, perp(axis_i.normalized())}, offset_(offset) {}

void RevoluteTranslationalJoint::residual(const Eigen::VectorXd& q, double, double* phi) const {
  phi[0] = gap_.value(q) - offset_;
}

void RevoluteTranslationalJoint::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  gap_.gradient(q, row0, out);
}

void RevoluteTranslationalJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double,
                                       double* out) const {
  out[0] = gap_.gamma(q, qd);
}

void RevoluteTranslationalJoint::coordinates(std::vector<int>& out) const {
  append_body_coordinates(gap_.a.body, out);
  append_body_coordinates(gap_.b.body, out);
}

}  // namespace periflex
