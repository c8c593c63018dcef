// The rigid-flexible joint: every particle p of a region of a peridynamic body moves rigidly
// with a rigid body v (usually a virtual, possibly massless body; Vieira et al.):
//
//   Phi_p = r_v + A(phi_v) s'_p - x_p = 0          two equations per particle,
//   s'_p  = A(phi_v0)^T (x_p0 - r_v0)             body-fixed position taken at set-up.
//
// With the ground as v (body index -1) the particles are clamped where they start:
// Phi_p = x_p0 - x_p.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "mbs/constraint.h"

namespace periflex {

class RigidFlexibleJoint : public Constraint {
 public:
  // body: rigid body index (coordinates 3*body .. 3*body+2), or -1 for the ground.
  // particle_coordinates: index in q of each particle's x; its y follows.
  // q0: the set-up configuration; it fixes the body-fixed particle positions s'_p.
  RigidFlexibleJoint(std::string name, int body, std::vector<int> particle_coordinates,
                     const Eigen::VectorXd& q0);

  const std::string& name() const override { return name_; }
  int rows() const override { return 2 * particle_count(); }
  void residual(const Eigen::VectorXd& q, double t, double* phi) const override;
  void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const override;
  void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const override;
  void coordinates(std::vector<int>& out) const override;

  // Rigid body the particles follow (-1: ground).
  int body() const { return body_; }
  int particle_count() const { return static_cast<int>(particle_coordinates_.size()); }
  // Index in q of the x coordinate of the k-th attached particle.
  const std::vector<int>& particle_coordinates() const { return particle_coordinates_; }
  // Body-fixed position s'_k of the k-th attached particle (global position for the ground).
  Vec2 local_position(int k) const { return Vec2(local_x_[k], local_y_[k]); }
  // Where the k-th particle should be at q: r_v + A(phi_v) s'_k.
  Vec2 target_position(const Eigen::VectorXd& q, int k) const;

  // Resultant the joint exerts on the rigid body for multipliers lambda (rows() values),
  // from the generalised constraint force -Phi_q^T lambda: force and torque about r_v.
  // The particles receive the opposite, +lambda_p each.
  void body_reaction(const Eigen::VectorXd& q, const double* lambda, Vec2& force, double& torque) const;

 private:
  std::string name_;
  int body_;
  std::vector<int> particle_coordinates_;
  // body-fixed particle positions, structure-of-arrays for the row loops
  std::vector<double> local_x_, local_y_;
};

// Factory the system builder calls for each AttachmentDef (particles from PdBody::particles_in).
// Throws InputError when the region holds no particle.
std::unique_ptr<RigidFlexibleJoint> make_rigid_flexible_joint(const std::string& name, int body,
                                                              const std::vector<int>& particle_coordinates,
                                                              const Eigen::VectorXd& q0);

}  // namespace periflex
