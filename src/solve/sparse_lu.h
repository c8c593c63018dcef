// Sparse LU of a matrix with a (nearly) symmetric pattern and a dominant diagonal, such as the
// iteration matrix of an implicit integrator, I - c df/dq on a particle grid.
//
// The fill-reducing order is approximate minimum degree on the pattern of A + A^T, applied to
// rows and columns alike (P^T A P), so the diagonal stays on the diagonal; the LU then prefers
// the diagonal pivot (threshold partial pivoting) and keeps that order unless a diagonal entry
// is small against its column. On the notched plate's HHT matrix (8,006 unknowns, 538,000
// entries) this factorises in 70-110 ms against 230 ms (plus 60 ms of analysis) for a column
// order from COLAMD, for the same fill: the symmetric order's elimination tree gives the
// supernodal LU larger dense blocks. (Eigen's SparseLU with AMDOrdering applies that order
// inverted and fills 6x more, 3.7 s on the same matrix; hence the permutation is done here.)
//
// The unknowns whose columns of A + A^T are the same (a particle's x and y; on the flexible
// slider-crank also runs of up to ten coordinates of particles eliminated onto one body, which
// reach the same region) are ordered as one. That
// also fills less where whole regions are coupled: on the flexible slider-crank's matrix (812
// unknowns) 58,000 factor entries, against 108,000 when ordered one by one and 60,000 in
// COLAMD's column order with row pivoting, which an earlier version therefore also tried on
// small matrices.
//
// The pattern is analysed once (ordering, permutation map, symbolic analysis) and factorised
// again for new values on the same pattern.
#pragma once

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

namespace periflex {

class SparseLu {
 public:
  // Orders and analyses the pattern of `a` (square, compressed, column-major).
  void analyse(const Eigen::SparseMatrix<double>& a);
  // True when `a` has the pattern last analysed.
  bool same_pattern(const Eigen::SparseMatrix<double>& a) const;
  // Factorises `a`; false when it is singular or its pattern is not the analysed one.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  // x with A x = b, after a successful factorize().
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Entries of the L and U factors.
  long factor_entries() const;

  // A diagonal pivot is kept while it is at least this fraction of its column's largest entry.
  static constexpr double kDiagonalPivotThreshold = 0.01;

 private:
  std::vector<int> position_;             // unknown i of A -> its place in P^T A P
  std::vector<int> outer_, inner_;        // the analysed pattern of A
  std::vector<int> permuted_index_;       // entry k of A's values -> its entry in P^T A P
  Eigen::SparseMatrix<double> permuted_;  // P^T A P
  using SymmetricLu = Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>>;
  std::unique_ptr<SymmetricLu> lu_;  // of P^T A P
};

}  // namespace periflex
