// Planar point kinematics shared by the joints, drivers and force elements of the catalogue
// (Nikravesh ch. 3-4). A point P on body i sits at r_i + A(phi_i) s'_i; its derivative with
// respect to phi_i is B(phi_i) s'_i = perp(A s'_i), and its second one is -A s'_i.
// The ground (body index -1) has no coordinates: its points are global and fixed.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/vec2.h"
#include "mbs/constraint.h"

namespace periflex {

// Appends one Jacobian entry; coordinates of the ground (col < 0) are skipped.
inline void put_entry(Triplets& out, int row, int col, double value) {
  if (col >= 0) out.emplace_back(row, col, value);
}

// A body-fixed point of a rigid body, or a global point of the ground.
struct BodyPoint {
  int body = -1;                 // rigid body index, -1 for the ground
  Vec2 local = Vec2::Zero();     // body-fixed s' (global position for the ground)

  bool on_ground() const { return body < 0; }
  // Index in q of x, y, phi of the body (-1 for the ground).
  int x_index() const { return body < 0 ? -1 : 3 * body; }
  int y_index() const { return body < 0 ? -1 : 3 * body + 1; }
  int phi_index() const { return body < 0 ? -1 : 3 * body + 2; }
  // The body's three coordinates (-1 each for the ground), for sparsity patterns.
  std::vector<int> coordinates() const { return {x_index(), y_index(), phi_index()}; }

  double angle(const Eigen::VectorXd& q) const { return body < 0 ? 0.0 : q[3 * body + 2]; }
  double angular_velocity(const Eigen::VectorXd& qd) const { return body < 0 ? 0.0 : qd[3 * body + 2]; }
  Vec2 origin(const Eigen::VectorXd& q) const {
    return body < 0 ? Vec2::Zero() : Vec2(q[3 * body], q[3 * body + 1]);
  }
  // Global arm s = A(phi) s' from the body origin to the point.
  Vec2 arm(const Eigen::VectorXd& q) const { return body < 0 ? local : Vec2(rotation(angle(q)) * local); }
  Vec2 position(const Eigen::VectorXd& q) const { return origin(q) + arm(q); }
  // r_dot + perp(s) phi_dot.
  Vec2 velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    if (body < 0) return Vec2::Zero();
    return Vec2(qd[3 * body], qd[3 * body + 1]) + perp(arm(q)) * qd[3 * body + 2];
  }
  // Quadratic-velocity part of the point's acceleration: -s phi_dot^2.
  Vec2 centripetal(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    const double w = angular_velocity(qd);
    return -arm(q) * w * w;
  }

  // Row `row` gets sign * c^T dP/dq for a global coefficient vector c.
  void add_gradient(Triplets& out, int row, const Vec2& c, double sign, const Eigen::VectorXd& q) const {
    if (body < 0) return;
    add_gradient_at(out, row, c, sign, arm(q));
  }
  // The same with the global arm given (one rotation per point when several rows need it).
  void add_gradient_at(Triplets& out, int row, const Vec2& c, double sign, const Vec2& global_arm) const {
    if (body < 0) return;
    put_entry(out, row, x_index(), sign * c.x());
    put_entry(out, row, y_index(), sign * c.y());
    put_entry(out, row, phi_index(), sign * c.dot(perp(global_arm)));
  }
  // Adds sign * F applied at the point to the generalised forces g (force and moment about r).
  void add_force(Eigen::VectorXd& g, const Vec2& force, double sign, const Eigen::VectorXd& q) const {
    if (body < 0) return;
    g[x_index()] += sign * force.x();
    g[y_index()] += sign * force.y();
    g[phi_index()] += sign * cross(arm(q), force);
  }
};

// f = (A_a e') . (P_b - P_a): the distance of P_b from P_a measured along an axis e' fixed in
// the body of P_a. Translational and revolute-translational joints use it with e' normal to
// the sliding axis, the position drivers with e' along their axis.
struct AxisGap {
  BodyPoint a, b;
  Vec2 axis = Vec2::UnitX();     // e', body-fixed in a (global when a is the ground)

  Vec2 global_axis(const Eigen::VectorXd& q) const {
    return a.on_ground() ? axis : Vec2(rotation(a.angle(q)) * axis);
  }
  double value(const Eigen::VectorXd& q) const { return global_axis(q).dot(b.position(q) - a.position(q)); }

  // df/dq: r_a: -n; phi_a: perp(n).d - n.perp(s_a); r_b: n; phi_b: n.perp(s_b).
  void gradient(const Eigen::VectorXd& q, int row, Triplets& out) const {
    const Vec2 n = global_axis(q);
    const Vec2 d = b.position(q) - a.position(q);
    if (!a.on_ground()) {
      put_entry(out, row, a.x_index(), -n.x());
      put_entry(out, row, a.y_index(), -n.y());
      put_entry(out, row, a.phi_index(), perp(n).dot(d) - n.dot(perp(a.arm(q))));
    }
    b.add_gradient(out, row, n, 1.0, q);
  }
  // Time derivative along qd.
  double rate(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    const Vec2 n = global_axis(q);
    const Vec2 d = b.position(q) - a.position(q);
    const Vec2 d_dot = b.velocity(q, qd) - a.velocity(q, qd);
    return perp(n).dot(d) * a.angular_velocity(qd) + n.dot(d_dot);
  }
  // Minus the quadratic-velocity part of f_ddot:
  //   n.d wa^2 - 2 wa perp(n).d_dot + n.(s_b wb^2 - s_a wa^2).
  double gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    const Vec2 n = global_axis(q);
    const Vec2 d = b.position(q) - a.position(q);
    const Vec2 d_dot = b.velocity(q, qd) - a.velocity(q, qd);
    const double wa = a.angular_velocity(qd);
    return n.dot(d) * wa * wa - 2.0 * wa * perp(n).dot(d_dot) -
           n.dot(b.centripetal(q, qd) - a.centripetal(q, qd));
  }
};

}  // namespace periflex
