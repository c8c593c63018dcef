#include "coupling/rigid_flexible_joint.h"

#include <utility>

#include "core/error.h"

namespace periflex {

namespace {

// pose of the followed body at q; the ground sits at the origin, unrotated
struct Pose {
  double x = 0.0, y = 0.0, phi = 0.0;
};

Pose pose_of(int body, const Eigen::VectorXd& q) {
  if (body < 0) return {};
  return {q[3 * body], q[3 * body + 1], q[3 * body + 2]};
}

}  // namespace

RigidFlexibleJoint::RigidFlexibleJoint(std::string name, int body, std::vector<int> particle_coordinates,
                                       const Eigen::VectorXd& q0)
    : name_(std::move(name)), body_(body), particle_coordinates_(std::move(particle_coordinates)) {
  // body-fixed positions s'_p = A(phi_v0)^T (x_p0 - r_v0), fixed once at set-up
  const Pose v = pose_of(body_, q0);
  const double c = std::cos(v.phi), s = std::sin(v.phi);
  const size_t n = particle_coordinates_.size();
  local_x_.resize(n);
  local_y_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int i = particle_coordinates_[k];
    const double dx = q0[i] - v.x, dy = q0[i + 1] - v.y;
    local_x_[k] = c * dx + s * dy;
    local_y_[k] = -s * dx + c * dy;
  }
}

Vec2 RigidFlexibleJoint::target_position(const Eigen::VectorXd& q, int k) const {
  const Pose v = pose_of(body_, q);
  const double c = std::cos(v.phi), s = std::sin(v.phi);
  return Vec2(v.x + c * local_x_[k] - s * local_y_[k], v.y + s * local_x_[k] + c * local_y_[k]);
}

void RigidFlexibleJoint::residual(const Eigen::VectorXd& q, double /*t*/, double* phi) const {
  // Phi_p = r_v + A s'_p - x_p
  const Pose v = pose_of(body_, q);
  const double c = std::cos(v.phi), s = std::sin(v.phi);
  const int n = particle_count();
  for (int k = 0; k < n; ++k) {
    const int i = particle_coordinates_[k];
    phi[2 * k] = v.x + c * local_x_[k] - s * local_y_[k] - q[i];
    phi[2 * k + 1] = v.y + s * local_x_[k] + c * local_y_[k] - q[i + 1];
  }
}

void RigidFlexibleJoint::jacobian(const Eigen::VectorXd& q, double /*t*/, int row0, Triplets& out) const {
  // rows of particle p: [ I  B(phi) s'_p ] on the body, -I on the particle
  const Pose v = pose_of(body_, q);
  const double c = std::cos(v.phi), s = std::sin(v.phi);
  const int n = particle_count();
  out.reserve(out.size() + static_cast<size_t>(n) * (body_ >= 0 ? 6 : 2));
  for (int k = 0; k < n; ++k) {
    const int i = particle_coordinates_[k];
    const int rx = row0 + 2 * k, ry = rx + 1;
    if (body_ >= 0) {
      const int b = 3 * body_;
      out.emplace_back(rx, b, 1.0);
      out.emplace_back(ry, b + 1, 1.0);
      out.emplace_back(rx, b + 2, -s * local_x_[k] - c * local_y_[k]);
      out.emplace_back(ry, b + 2, c * local_x_[k] - s * local_y_[k]);
    }
    out.emplace_back(rx, i, -1.0);
    out.emplace_back(ry, i + 1, -1.0);
  }
}

void RigidFlexibleJoint::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double /*t*/,
                               double* out) const {
  // gamma_p = A(phi) s'_p phi_dot^2 (zero for the ground)
  const int n = particle_count();
  if (body_ < 0) {
    for (int k = 0; k < 2 * n; ++k) out[k] = 0.0;
    return;
  }
  const Pose v = pose_of(body_, q);
  const double c = std::cos(v.phi), s = std::sin(v.phi);
  const double w2 = qd[3 * body_ + 2] * qd[3 * body_ + 2];
  for (int k = 0; k < n; ++k) {
    out[2 * k] = (c * local_x_[k] - s * local_y_[k]) * w2;
    out[2 * k + 1] = (s * local_x_[k] + c * local_y_[k]) * w2;
  }
}

void RigidFlexibleJoint::coordinates(std::vector<int>& out) const {
  if (body_ >= 0) {
    for (int j = 0; j < 3; ++j) out.push_back(3 * body_ + j);
  }
  for (int i : particle_coordinates_) {
    out.push_back(i);
    out.push_back(i + 1);
  }
}

void RigidFlexibleJoint::body_reaction(const Eigen::VectorXd& q, const double* lambda, Vec2& force,
                                       double& torque) const {
  // -Phi_q^T lambda restricted to the body: force -sum lambda_p, torque -sum (B s'_p) . lambda_p
  force.setZero();
  torque = 0.0;
  if (body_ < 0) {
    for (int k = 0; k < particle_count(); ++k) force -= Vec2(lambda[2 * k], lambda[2 * k + 1]);
    return;
  }
  const double phi = q[3 * body_ + 2];
  const double c = std::cos(phi), s = std::sin(phi);
  for (int k = 0; k < particle_count(); ++k) {
    const double lx = lambda[2 * k], ly = lambda[2 * k + 1];
    force.x() -= lx;
    force.y() -= ly;
    torque -= (-s * local_x_[k] - c * local_y_[k]) * lx + (c * local_x_[k] - s * local_y_[k]) * ly;
  }
}

std::unique_ptr<RigidFlexibleJoint> make_rigid_flexible_joint(const std::string& name, int body,
                                                              const std::vector<int>& particle_coordinates,
                                                              const Eigen::VectorXd& q0) {
  // an empty region is almost always a mistyped region box; say so rather than attach nothing
  if (particle_coordinates.empty()) {
    SourceLocation where;
    where.key = "attachment." + name + ".region";
    throw InputError(where, "the attachment region holds no particle of the flexible body");
  }
  for (int i : particle_coordinates) {
    if (i < 0 || i + 1 >= q0.size()) {
      SourceLocation where;
      where.key = "attachment." + name;
      throw InputError(where, "particle coordinate index outside the coordinate vector");
    }
  }
  if (body >= 0 && 3 * body + 2 >= q0.size()) {
    SourceLocation where;
    where.key = "attachment." + name + ".body";
    throw InputError(where, "rigid body index outside the coordinate vector");
  }
  return std::make_unique<RigidFlexibleJoint>(name, body, particle_coordinates, q0);
}

}  // namespace periflex
