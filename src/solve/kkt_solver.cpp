#include "solve/kkt_solver.h"

#include <algorithm>

namespace periflex {

bool KktSolver::factorize(const Eigen::VectorXd& w, const Triplets& jacobian, int m) {
  const int n = static_cast<int>(w.size());
  // diagonal entries are always stored (even zero masses) so the pattern never changes
  triplets_.clear();
  triplets_.reserve(n + 2 * jacobian.size());
  for (int i = 0; i < n; ++i) triplets_.emplace_back(i, i, w[i]);
  for (const auto& e : jacobian) {
    triplets_.emplace_back(n + e.row(), e.col(), e.value());
    triplets_.emplace_back(e.col(), n + e.row(), e.value());
  }
  matrix_.resize(n + m, n + m);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  matrix_.makeCompressed();

  // re-analyse only when the pattern differs from the analysed one
  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  const int nnz = static_cast<int>(matrix_.nonZeros());
  const bool same = outer_.size() == static_cast<size_t>(n + m + 1) && inner_.size() == static_cast<size_t>(nnz) &&
                    std::equal(outer_.begin(), outer_.end(), outer) && std::equal(inner_.begin(), inner_.end(), inner);
  if (!same) {
    outer_.assign(outer, outer + n + m + 1);
    inner_.assign(inner, inner + nnz);
    lu_.analyzePattern(matrix_);
    ++analyses_;
  }
  lu_.factorize(matrix_);
  return lu_.info() == Eigen::Success;
}

Eigen::VectorXd KktSolver::solve(const Eigen::VectorXd& rhs) const { return lu_.solve(rhs); }

}  // namespace periflex
