#include "solve/redundancy.h"

#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseQR>
#include <algorithm>

namespace periflex {

// Above this many rows the dense QR would cost more than the sparse one.
constexpr int kDenseRowLimit = 600;

std::vector<int> dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) {
  const int m = static_cast<int>(j.rows());
  std::vector<int> dependent;
  if (m == 0) return dependent;
  // columns of J^T are the equations; the pivoting order puts independent ones first
  if (m <= kDenseRowLimit) {
    const Eigen::MatrixXd jt = Eigen::MatrixXd(j.transpose());
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jt);
    qr.setThreshold(relative_threshold);
    const auto& perm = qr.colsPermutation().indices();
    for (int k = static_cast<int>(qr.rank()); k < m; ++k) dependent.push_back(perm[k]);
  } else {
    Eigen::SparseMatrix<double> jt = j.transpose();
    jt.makeCompressed();
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
    double max_norm = 0.0;
    for (int c = 0; c < jt.cols(); ++c) max_norm = std::max(max_norm, jt.col(c).norm());
    qr.setPivotThreshold(relative_threshold * max_norm);
    qr.compute(jt);
    const auto& perm = qr.colsPermutation().indices();
    for (int k = static_cast<int>(qr.rank()); k < m; ++k) dependent.push_back(perm[k]);
  }
  std::sort(dependent.begin(), dependent.end());
  return dependent;
}

int column_rank(const Eigen::MatrixXd& j, double relative_threshold) {
  if (j.cols() == 0) return 0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(j);
  qr.setThreshold(relative_threshold);
  return static_cast<int>(qr.rank());
}

}  // namespace periflex
