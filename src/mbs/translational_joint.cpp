#include "mbs/translational_joint.h"

#include "mbs/revolute_joint.h"

namespace periflex {

TranslationalJoint::TranslationalJoint(std::string name, BodyPoint p_i, BodyPoint p_j, const Vec2& axis_i,
                                       double relative_angle)
    : name_(std::move(name)), gap_{p_i, p_j, perp(axis_i.normalized())}, relative_angle_(relative_angle) {}

void TranslationalJoint::residual(const Eigen::VectorXd& q, double, double* phi) const {
  phi[0] = gap_.value(q);
  phi[1] = gap_.b.angle(q) - gap_.a.angle(q) - relative_angle_;
}

void TranslationalJoint::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  gap_.gradient(q, row0, out);
  put_entry(out, row0 + 1, gap_.b.phi_index(), 1.0);
  put_entry(out, row0 + 1, gap_.a.phi_index(), -1.0);
}

void TranslationalJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, double* out) const {
  out[0] = gap_.gamma(q, qd);
  out[1] = 0.0;
}

void TranslationalJoint::coordinates(std::vector<int>& out) const {
  append_body_coordinates(gap_.a.body, out);
  append_body_coordinates(gap_.b.body, out);
}

}  // namespace periflex
