// Finds the dependent rows of a constraint Jacobian, at a cost about linear in its size.
//
// The large Jacobians the solver meets are rigid-body rows (joints, drivers) over a few body
// coordinates, and rigid-flexible joints: two rows per attached particle, an identity on the
// particle's own columns. Columns marked eliminable (the particle coordinates) are removed
// first by sparse Gaussian elimination: for each, one row holding it becomes its pivot (that
// row is independent: after the elimination no other row touches the column) and is
// subtracted from the other rows holding it. A particle held by two bodies thus leaves one row
// pair of the first joint as pivots and turns the second joint's pair into a row over the two
// bodies' coordinates only. What remains is the small system of the rigid and virtual bodies;
// rows with a column of their own are peeled off, and a rank-revealing QR of the rest's
// transpose (column-pivoted Householder, dense when small or thin, sparse QR otherwise)
// decides which rows depend on the others.
//
// With a right-hand side v (e.g. Phi_t: what the drivers impose on the velocities), each
// dependency y (y^T Phi_q = 0) is also checked for y^T v = 0: a dependent row whose v the
// others contradict makes the equations unsolvable, and its rows are reported.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace periflex {

struct RowAnalysisOptions {
  std::vector<char> eliminable;                  // per column (empty: none)
  const Eigen::VectorXd* rhs = nullptr;          // per row, checked for consistency (dense QR only)
  const Eigen::VectorXd* column_weight = nullptr;  // metric of the QR: column c scaled by
                                                   // 1/sqrt(w_c), each row then to unit length
  double relative_threshold = 1e-9;              // pivots below this times the largest count as zero
};

struct RowDependence {
  std::vector<int> dependent;    // rows that depend on the others, increasing
  std::vector<int> conflicting;  // rows of dependencies whose rhs disagree, increasing (empty: none)
  std::vector<int> pivots;       // rows that eliminated a column (independent), increasing
};

RowDependence find_dependent_rows(const Eigen::SparseMatrix<double>& j, const RowAnalysisOptions& options);

// Rows of j (m x n) that depend on the others, in increasing order; keeping all the other
// rows leaves a full-row-rank Jacobian. `relative_threshold` scales the largest pivot.
std::vector<int> dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold = 1e-9);

// Numerical rank of the columns of j.
int column_rank(const Eigen::MatrixXd& j, double relative_threshold = 1e-9);

}  // namespace periflex
