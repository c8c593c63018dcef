// Finds the dependent rows of a constraint Jacobian with a rank-revealing QR of Phi_q^T
// (dense column-pivoted Householder for small systems, sparse QR for large ones).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace periflex {

// Rows of j (m x n) that depend on the others, in increasing order; keeping all the other
// rows leaves a full-row-rank Jacobian. `relative_threshold` scales the largest pivot.
std::vector<int> dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold = 1e-9);

// Numerical rank of the columns of j.
int column_rank(const Eigen::MatrixXd& j, double relative_threshold = 1e-9);

}  // namespace periflex
