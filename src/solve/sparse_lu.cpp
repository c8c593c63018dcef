#include "solve/sparse_lu.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <utility>

namespace periflex {

namespace {

template <class Lu>
long entries(const Lu& lu) {
  return lu.nnzL() + lu.nnzU();
}

}  // namespace

void SparseLu::analyse(const Eigen::SparseMatrix<double>& a) {
  const int n = static_cast<int>(a.cols());
  const int nnz = static_cast<int>(a.nonZeros());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  outer_.assign(outer, outer + n + 1);
  inner_.assign(inner, inner + nnz);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int> amd;
  amd(a, order);
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse = order.inverse();
  position_.assign(inverse.indices().data(), inverse.indices().data() + n);

  // P^T A P built column by column (7 ms on the plate's matrix; Eigen's permutation product
  // takes 34), remembering where each entry of A lands
  permuted_.resize(n, n);
  permuted_.resizeNonZeros(nnz);
  int* permuted_outer = permuted_.outerIndexPtr();
  permuted_outer[0] = 0;
  for (int j = 0; j < n; ++j) permuted_outer[position_[j] + 1] = outer[j + 1] - outer[j];
  for (int j = 0; j < n; ++j) permuted_outer[j + 1] += permuted_outer[j];
  permuted_index_.assign(nnz, 0);
  std::vector<std::pair<int, int>> column;  // (row in P^T A P, entry of A)
  for (int j = 0; j < n; ++j) {
    column.clear();
    for (int k = outer[j]; k < outer[j + 1]; ++k) column.emplace_back(position_[inner[k]], k);
    std::sort(column.begin(), column.end());
    int slot = permuted_outer[position_[j]];
    for (const auto& [row, k] : column) {
      permuted_.innerIndexPtr()[slot] = row;
      permuted_.valuePtr()[slot] = a.valuePtr()[k];
      permuted_index_[k] = slot++;
    }
  }
  lu_ = std::make_unique<SymmetricLu>();
  lu_->setPivotThreshold(kDiagonalPivotThreshold);
  lu_->analyzePattern(permuted_);
  use_column_order_ = false;
  trial_pending_ = nnz <= kTrialEntries;
  column_lu_.reset();
  if (trial_pending_) {
    column_lu_ = std::make_unique<ColumnLu>();
    column_lu_->analyzePattern(a);
  }
}

bool SparseLu::same_pattern(const Eigen::SparseMatrix<double>& a) const {
  const int nnz = static_cast<int>(a.nonZeros());
  return a.isCompressed() && outer_.size() == static_cast<size_t>(a.outerSize() + 1) &&
         inner_.size() == static_cast<size_t>(nnz) && std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
}

bool SparseLu::factorize(const Eigen::SparseMatrix<double>& a) {
  if (!lu_ && !column_lu_) return false;
  if (!same_pattern(a)) return false;  // its values would land in the wrong places
  if (use_column_order_) {
    column_lu_->factorize(a);
    return column_lu_->info() == Eigen::Success;
  }
  const double* values = a.valuePtr();
  double* permuted = permuted_.valuePtr();
  for (size_t k = 0; k < permuted_index_.size(); ++k) permuted[permuted_index_[k]] = values[k];
  lu_->factorize(permuted_);
  const bool factorised = lu_->info() == Eigen::Success;
  if (trial_pending_) {
    // the first factorisation of a small pattern: the column order too, and the better kept
    trial_pending_ = false;
    column_lu_->factorize(a);
    use_column_order_ = column_lu_->info() == Eigen::Success &&
                        (!factorised || entries(*column_lu_) < kColumnOrderRatio * entries(*lu_));
    if (use_column_order_) {
      lu_.reset();
      return true;
    }
    column_lu_.reset();
  }
  return factorised;
}

long SparseLu::factor_entries() const {
  if (use_column_order_) return entries(*column_lu_);
  return lu_ ? entries(*lu_) : 0;
}

Eigen::VectorXd SparseLu::solve(const Eigen::VectorXd& b) const {
  if (use_column_order_) return column_lu_->solve(b);
  const Eigen::Index n = b.size();
  Eigen::VectorXd permuted_b(n);
  for (Eigen::Index i = 0; i < n; ++i) permuted_b[position_[i]] = b[i];
  const Eigen::VectorXd y = lu_->solve(permuted_b);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = y[position_[i]];
  return x;
}

}  // namespace periflex
