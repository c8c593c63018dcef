#include "mbs/rigid_joint.h"

#include "mbs/revolute_joint.h"

namespace periflex {

RigidJoint::RigidJoint(std::string name, BodyPoint p_i, BodyPoint p_j, double relative_angle)
    : name_(std::move(name)), p_i_(p_i), p_j_(p_j), relative_angle_(relative_angle) {}

void RigidJoint::residual(const Eigen::VectorXd& q, double, double* phi) const {
  const Vec2 d = p_i_.position(q) - p_j_.position(q);
  phi[0] = d.x();
  phi[1] = d.y();
  phi[2] = p_j_.angle(q) - p_i_.angle(q) - relative_angle_;
}

void RigidJoint::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  // two point rows as in the revolute joint, then the angle row
  for (int k = 0; k < 2; ++k) {
    const Vec2 c = k == 0 ? Vec2::UnitX() : Vec2::UnitY();
    p_i_.add_gradient(out, row0 + k, c, 1.0, q);
    p_j_.add_gradient(out, row0 + k, c, -1.0, q);
  }
  put_entry(out, row0 + 2, p_j_.phi_index(), 1.0);
  put_entry(out, row0 + 2, p_i_.phi_index(), -1.0);
}

void RigidJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, double* out) const {
  const Vec2 g = -(p_i_.centripetal(q, qd) - p_j_.centripetal(q, qd));
  out[0] = g.x();
  out[1] = g.y();
  out[2] = 0.0;
}

void RigidJoint::coordinates(std::vector<int>& out) const {
  append_body_coordinates(p_i_.body, out);
  append_body_coordinates(p_j_.body, out);
}

}  // namespace periflex
