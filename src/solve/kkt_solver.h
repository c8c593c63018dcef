// The sparse augmented (saddle-point) system of constrained dynamics,
//   [ W   J^T ] [ x  ]   [ a ]
//   [ J   0   ] [ mu ] = [ b ],
// with W diagonal (masses for accelerations, weights for projections) and J the active rows of
// Phi_q over the constrained coordinates.
//
// The system is scaled first (coordinates by 1/sqrt(w), equations to a unit largest entry) so
// that partial pivoting keeps to the fill-reducing order. A coordinate that appears in very
// many equations (a virtual body holding hundreds of particles) is a "hub": a dense row and
// column that make a general sparse LU cost far more than linear. Hubs, and the equations that
// involve hubs only, are therefore kept out of the sparse factorisation and solved through
// their small dense Schur complement, so the cost grows about linearly with the attached
// particles. Without hubs (or when the split is singular) the whole matrix is factorised.
// The sparsity pattern is analysed once and only refactorised while it stays the same.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

#include "mbs/constraint.h"

namespace periflex {

class KktSolver {
 public:
  // Assembles from the diagonal w (size n) and the triplets of J (rows local to the m active
  // equations, columns local to the n coordinates), and factorises. Returns false when the
  // matrix is singular. `coupling`, when given, holds off-diagonal entries of W (both halves of
  // a symmetric block, e.g. a rigid body that carries eliminated particles).
  bool factorize(const Eigen::VectorXd& w, const Triplets& jacobian, int m, const Triplets* coupling = nullptr);
  // Solves for the right-hand side [a; b] (size n + m); the result has the same layout.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  // Times the pattern had to be analysed (1 while the constraint set stays the same).
  int analyses() const { return analyses_; }
  // Unknowns solved through the dense Schur complement (0: one sparse factorisation).
  int hub_unknowns() const { return static_cast<int>(hub_.size()); }

  // A coordinate in more equations than this is a hub.
  static constexpr int kHubDegree = 48;

 private:
  bool factorize_sparse(const Triplets& triplets, int size);
  bool factorize_split(const Eigen::VectorXd& w, const Triplets& jacobian, int m, const Triplets* coupling);

  Eigen::SparseMatrix<double> matrix_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::vector<int> outer_, inner_;  // the analysed pattern
  Eigen::VectorXd scale_;           // symmetric diagonal scaling D of the matrix, D K D
  Triplets triplets_;
  int analyses_ = 0;

  // the split: unknowns in the sparse part (in order) and hub unknowns, both as indices of [x; mu]
  bool split_failed_ = false;
  std::vector<int> sparse_, hub_;
  std::vector<int> position_;       // unknown -> index within its part
  Eigen::MatrixXd coupling_;        // B: sparse part x hubs
  Eigen::MatrixXd solved_coupling_; // A^-1 B
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_;  // E (C - B^T A^-1 B) E, equilibrated
  Eigen::VectorXd schur_scale_;                  // E
};

}  // namespace periflex
