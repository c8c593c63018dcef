#include "mbs/revolute_joint.h"

namespace periflex {

void append_body_coordinates(int body, std::vector<int>& out) {
  if (body < 0) return;
  for (int k = 0; k < 3; ++k) out.push_back(3 * body + k);
}

RevoluteJoint::RevoluteJoint(std::string name, BodyPoint p_i, BodyPoint p_j)
    : name_(std::move(name)), p_i_(p_i), p_j_(p_j) {}

void RevoluteJoint::residual(const Eigen::VectorXd& q, double, double* phi) const {
  const Vec2 d = p_i_.position(q) - p_j_.position(q);
  phi[0] = d.x();
  phi[1] = d.y();
}

void RevoluteJoint::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  // each row is one global component of P_i - P_j; each arm rotated once for both rows
  const Vec2 arm_i = p_i_.arm(q), arm_j = p_j_.arm(q);
  for (int k = 0; k < 2; ++k) {
    const Vec2 c = k == 0 ? Vec2::UnitX() : Vec2::UnitY();
    p_i_.add_gradient_at(out, row0 + k, c, 1.0, arm_i);
    p_j_.add_gradient_at(out, row0 + k, c, -1.0, arm_j);
  }
}

void RevoluteJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, double* out) const {
  // gamma = s_i w_i^2 - s_j w_j^2
  const Vec2 g = -(p_i_.centripetal(q, qd) - p_j_.centripetal(q, qd));
  out[0] = g.x();
  out[1] = g.y();
}

void RevoluteJoint::coordinates(std::vector<int>& out) const {
  append_body_coordinates(p_i_.body, out);
  append_body_coordinates(p_j_.body, out);
}

}  // namespace periflex
