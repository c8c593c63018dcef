// The sparse augmented (saddle-point) system of constrained dynamics,
//   [ W   J^T ] [ x  ]   [ a ]
//   [ J   0   ] [ mu ] = [ b ],
// with W diagonal (masses for accelerations, weights for projections) and J the active rows of
// Phi_q over the constrained coordinates. The sparsity pattern is analysed once (fill-reducing
// COLAMD ordering) and only refactorised while it stays the same, so the cost of each step
// grows about linearly with the constrained coordinates.
#pragma once

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

#include "mbs/constraint.h"

namespace periflex {

class KktSolver {
 public:
  // Assembles from the diagonal w (size n) and the triplets of J (rows local to the m active
  // equations, columns local to the n coordinates), and factorises. Returns false when the
  // matrix is singular.
  bool factorize(const Eigen::VectorXd& w, const Triplets& jacobian, int m);
  // Solves for the right-hand side [a; b] (size n + m); the result has the same layout.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  // Times the pattern had to be analysed (1 while the constraint set stays the same).
  int analyses() const { return analyses_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::vector<int> outer_, inner_;  // the analysed pattern
  Triplets triplets_;
  int analyses_ = 0;
};

}  // namespace periflex
