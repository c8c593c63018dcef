#include "mbs/revolute_revolute_joint.h"

#include "mbs/revolute_joint.h"

namespace periflex {

RevoluteRevoluteJoint::RevoluteRevoluteJoint(std::string name, BodyPoint p_i, BodyPoint p_j, double length)
    : name_(std::move(name)), p_i_(p_i), p_j_(p_j), length_(length) {}

void RevoluteRevoluteJoint::residual(const Eigen::VectorXd& q, double, double* phi) const {
  const Vec2 d = p_j_.position(q) - p_i_.position(q);
  phi[0] = (d.squaredNorm() - length_ * length_) / (2.0 * length_);
}

void RevoluteRevoluteJoint::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  // Phi_q = d^T (dP_j/dq - dP_i/dq) / L
  const Vec2 c = (p_j_.position(q) - p_i_.position(q)) / length_;
  p_j_.add_gradient(out, row0, c, 1.0, q);
  p_i_.add_gradient(out, row0, c, -1.0, q);
}

void RevoluteRevoluteJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, double* out) const {
  // Phi_ddot = (d_dot.d_dot + d.d_ddot) / L; gamma is minus its velocity-quadratic part
  const Vec2 d = p_j_.position(q) - p_i_.position(q);
  const Vec2 d_dot = p_j_.velocity(q, qd) - p_i_.velocity(q, qd);
  const Vec2 quad = p_j_.centripetal(q, qd) - p_i_.centripetal(q, qd);
  out[0] = -(d_dot.squaredNorm() + d.dot(quad)) / length_;
}

void RevoluteRevoluteJoint::coordinates(std::vector<int>& out) const {
  append_body_coordinates(p_i_.body, out);
  append_body_coordinates(p_j_.body, out);
}

}  // namespace periflex
