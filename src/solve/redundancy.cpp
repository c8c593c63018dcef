#include "solve/redundancy.h"

#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseQR>
#include <algorithm>

namespace periflex {

// Above this many rows the dense QR would cost more than the sparse one.
constexpr int kDenseRowLimit = 600;

// Rank-revealing QR of the rows of j (all of them candidates); dependent ones, in j's numbering.
static std::vector<int> qr_dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) {
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
  return dependent;
}

std::vector<int> dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) {
  const int m = static_cast<int>(j.rows());
  const int n = static_cast<int>(j.cols());
  // a row with a nonzero in a column no other remaining row touches cannot take part in a
  // dependency: peel such rows off first (every particle row of a rigid-flexible joint has
  // its particle's column to itself), so the QR only sees the few rows that could be dependent
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = j;
  std::vector<char> remaining(m, 1);
  std::vector<int> column_count(n, 0);
  auto significant = [&](int r, double v) {
    return std::abs(v) > 1e-12 * rows.row(r).cwiseAbs().sum();
  };
  for (int r = 0; r < m; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      if (significant(r, it.value())) ++column_count[it.col()];
    }
  }
  for (int pass = 0; pass < 4; ++pass) {
    bool peeled = false;
    for (int r = 0; r < m; ++r) {
      if (!remaining[r]) continue;
      bool has_private = false;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it && !has_private; ++it) {
        has_private = significant(r, it.value()) && column_count[it.col()] == 1;
      }
      if (!has_private) continue;
      remaining[r] = 0;
      peeled = true;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
        if (significant(r, it.value())) --column_count[it.col()];
      }
    }
    if (!peeled) break;
  }

  // the rest goes through the rank-revealing QR
  std::vector<int> kept;
  for (int r = 0; r < m; ++r) {
    if (remaining[r]) kept.push_back(r);
  }
  std::vector<int> dependent;
  if (kept.empty()) return dependent;
  Eigen::SparseMatrix<double, Eigen::RowMajor> sub(static_cast<int>(kept.size()), n);
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t k = 0; k < kept.size(); ++k) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, kept[k]); it; ++it) {
      entries.emplace_back(static_cast<int>(k), it.col(), it.value());
    }
  }
  sub.setFromTriplets(entries.begin(), entries.end());
  for (int k : qr_dependent_rows(Eigen::SparseMatrix<double>(sub), relative_threshold)) dependent.push_back(kept[k]);
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
