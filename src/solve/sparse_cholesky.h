// Supernodal sparse Cholesky, A = L L^T, of a symmetric positive definite matrix, through
// CHOLMOD (SuiteSparse): the fill-reducing order (approximate minimum degree) and the symbolic
// analysis once per pattern, then a numerical factorisation per set of values, whose dense
// supernodal blocks run in the BLAS (OpenBLAS where installed, one thread).
//
// Why not Eigen: Eigen has no supernodal Cholesky. On the notched plate's HHT matrix (8,006
// unknowns, 4.8e8 flops for L) Eigen's SimplicialLDLT takes 150 ms, its SparseLU of the whole
// matrix (twice the flops) 80-110 ms, CHOLMOD 35-60 ms (docs/solver.md).
//
// Usage:
//   SparseCholesky chol;
//   chol.analyse(n, start, rows);                  // lower triangle, compressed columns
//   if (chol.factorize(values)) x = chol.solve(b); // false: not positive definite
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace periflex {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // Orders and analyses the lower triangle of an n x n symmetric matrix given by its
  // compressed columns (rows of column j: rows[start[j] .. start[j + 1]), ascending, every row
  // >= j, the diagonal present). The arrays are copied.
  void analyse(int n, const std::vector<int>& start, const std::vector<int>& rows);
  bool analysed() const;
  // Factorises the matrix whose lower-triangle values are `values` (in the analysed pattern's
  // order); false when it is not positive definite (or not finite).
  bool factorize(const double* values);
  // x with A x = b, after a successful factorize() (NaN otherwise).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  // Entries of L.
  long factor_entries() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
