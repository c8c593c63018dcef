// Rigid-flexible joints solved by elimination. A particle p held by a joint to body v moves as
// x_p = r_v + A(phi_v) s'_p, so in any of the linear systems the stepper solves,
//
//   W z + Phi_q^T lambda = a,   Phi_q z = e,
//
// its two rows read B_p z_v - z_p = e_p with B_p = [I, A'(phi_v) s'_p], and the particle's own
// equation gives lambda_p = w_p z_p - a_p. Substituting both into the body's equation leaves
//
//   (W_v + sum_p w_p B_p^T B_p) z_v + (other rows) = a_v + sum_p B_p^T (a_p + w_p e_p),
//
// after which z_p = B_p z_v - e_p. This is the same solution as the full system, exactly, at a
// cost linear in the attached particles and with no particle in the matrix: a plate held by two
// grips of hundreds of particles each leaves a handful of rigid unknowns. The same algebra
// serves the accelerations (a = g, e = gamma with its Baumgarte terms), the position projection
// (a = 0, e = -Phi) and the velocity projection (a = 0, e = -(Phi_q qd + Phi_t)).
//
// A particle is eliminated when both its rows in the joint stay (are not left out as
// dependent), no other staying row reaches it, and it is not imposed; otherwise its rows stay
// in the matrix. (A plate held whole by two grips keeps in the matrix only the few particles
// whose rows in the second grip's joint tie the two grips together.)
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbs/constraint.h"
#include "model/system_model.h"

namespace periflex {

class CondensedAttachments {
 public:
  // Chooses the joints to eliminate (none when !enabled). active_index: global row -> active
  // row (-1 dropped).
  void build(const SystemModel& model, const std::vector<int>& active_index, bool enabled = true);
  bool empty() const { return particles_.empty(); }
  // Whether constraint block k of the model is eliminated whole, and whether global row r is.
  bool block_condensed(size_t k) const { return k < block_condensed_.size() && block_condensed_[k]; }
  bool row_condensed(int r) const { return r < static_cast<int>(row_condensed_.size()) && row_condensed_[r]; }
  // Whether global coordinate c is an eliminated particle coordinate.
  bool coordinate_condensed(int c) const { return c < static_cast<int>(slaved_.size()) && slaved_[c]; }

  // Body offsets A(phi_v) s'_p at q; call before the functions below.
  void update(const Eigen::VectorXd& q);

  // Adds sum_p w_p B_p^T B_p: diagonal entries into diag, off-diagonal ones as triplets, both at
  // the reduced index of each body coordinate (reduced[c], c global).
  void add_body_blocks(const Eigen::VectorXd& w, const std::vector<int>& reduced, Eigen::VectorXd& diag,
                       Triplets& coupling) const;
  // Adds sum_p B_p^T (a_p + w_p e_p) to rhs at the reduced body indices. a and w are indexed by
  // global coordinate (a may be null: zero), e by global row.
  void add_body_rhs(const double* a, const Eigen::VectorXd& w, const double* e, const std::vector<int>& reduced,
                    Eigen::VectorXd& rhs) const;
  // z_p = B_p z_v - e_p for every eliminated particle; z holds the bodies' values (global index).
  void recover(const double* e, Eigen::VectorXd& z) const;
  // e_p = Phi_q qd + Phi_t of the eliminated rows (velocity residual), into out by global row.
  void velocity_residual(const Eigen::VectorXd& qd, double* out) const;
  // lambda_p = w_p z_p - a_p for every eliminated row, into lambda at the active row index.
  void multipliers(const Eigen::VectorXd& w, const Eigen::VectorXd& z, const double* a,
                   const std::vector<int>& active_index, Eigen::VectorXd& lambda) const;

 private:
  struct Particle {
    int coordinate;  // x of the particle in q
    int body;        // -1: the ground
    int row;         // global row of its x equation
    double local_x, local_y;  // s'_p
    double world_x = 0, world_y = 0;  // A(phi) s'_p at the last update
  };
  std::vector<Particle> particles_;
  std::vector<char> block_condensed_, row_condensed_, slaved_;
};

}  // namespace periflex
