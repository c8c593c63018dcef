#include "solve/iteration_matrix_factors.h"

#include <algorithm>
#include <cmath>

namespace periflex {

void IterationMatrixFactors::analyse(const Eigen::SparseMatrix<double>& s, const Eigen::VectorXd& free_mass) {
  n_ = static_cast<int>(s.cols());
  const int* outer = s.outerIndexPtr();
  const int* inner = s.innerIndexPtr();
  outer_.assign(outer, outer + n_ + 1);
  inner_.assign(inner, inner + outer[n_]);
  splittable_ = split_ = whole_analysed_ = false;
  free_.clear();
  other_.clear();

  // each coordinate's set and its place there
  std::vector<int> place(static_cast<size_t>(n_));
  std::vector<char> is_free(static_cast<size_t>(n_), 0);
  for (int i = 0; i < n_; ++i) {
    is_free[i] = free_mass.size() == n_ && free_mass[i] > 0.0;
    std::vector<int>& set = is_free[i] ? free_ : other_;
    place[i] = static_cast<int>(set.size());
    set.push_back(i);
  }
  // no constrained row may read a free coordinate (S_CF = 0)
  bool triangular = !free_.empty();
  for (int j : free_)
    for (int k = outer[j]; k < outer[j + 1] && triangular; ++k) triangular = is_free[inner[k]];
  if (!triangular) return;

  const int nf = static_cast<int>(free_.size()), nc = static_cast<int>(other_.size());
  mass_.resize(nf);
  for (int f = 0; f < nf; ++f) mass_[f] = free_mass[free_[f]];

  // the lower triangle of the free block: entry (i, j) lands at (max, min) of their places, as
  // the row's own value (source 0) or the transposed one (source 1). Walking S's columns in
  // order, a column of the triangle receives its own entries first, then the transposed ones,
  // each run with ascending rows: merged, not sorted.
  struct Landing {
    int row, index;
  };
  std::vector<int> count(static_cast<size_t>(nf) + 1, 0), own(static_cast<size_t>(nf), 0);
  for (int j : free_)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int r = place[inner[k]], c = place[j];
      ++count[std::min(r, c) + 1];
      own[c] += r >= c;
    }
  for (int c = 0; c < nf; ++c) count[c + 1] += count[c];
  std::vector<Landing> landing(static_cast<size_t>(count[nf]));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int j : free_)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int r = place[inner[k]], c = place[j];
      landing[fill[std::min(r, c)]++] = {std::max(r, c), k};
    }
  lower_start_.assign(1, 0);
  lower_rows_.clear();
  source_.clear();
  diagonal_.assign(static_cast<size_t>(nf), -1);
  for (int c = 0; c < nf; ++c) {
    const Landing* a = landing.data() + count[c];
    const Landing* a_end = a + own[c];
    const Landing* b = a_end;
    const Landing* b_end = landing.data() + count[c + 1];
    while (a != a_end || b != b_end) {
      const int row = b == b_end || (a != a_end && a->row <= b->row) ? a->row : b->row;
      lower_rows_.push_back(row);
      source_.push_back(a != a_end && a->row == row ? (a++)->index : -1);
      source_.push_back(b != b_end && b->row == row ? (b++)->index : -1);
    }
    const int column_first = lower_start_.back();
    lower_start_.push_back(static_cast<int>(lower_rows_.size()));
    if (column_first < lower_start_.back() && lower_rows_[column_first] == c) diagonal_[c] = column_first;
    if (diagonal_[c] < 0) return;  // no diagonal: S is factorised whole
  }
  lower_values_.assign(lower_rows_.size(), 0.0);

  // S_FC, and S_CC in compressed columns of the other coordinates
  coupling_row_.clear();
  coupling_col_.clear();
  coupling_source_.clear();
  std::vector<int> other_outer(1, 0), other_inner;
  other_source_.clear();
  for (int j : other_) {
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      if (is_free[i]) {
        coupling_row_.push_back(place[i]);
        coupling_col_.push_back(place[j]);
        coupling_source_.push_back(k);
      } else {
        other_inner.push_back(place[i]);
        other_source_.push_back(k);
      }
    }
    other_outer.push_back(static_cast<int>(other_inner.size()));
  }
  coupling_values_.assign(coupling_source_.size(), 0.0);
  if (nc > 0) {
    other_block_.resize(nc, nc);
    other_block_.resizeNonZeros(static_cast<Eigen::Index>(other_inner.size()));
    std::copy(other_outer.begin(), other_outer.end(), other_block_.outerIndexPtr());
    std::copy(other_inner.begin(), other_inner.end(), other_block_.innerIndexPtr());
    std::fill(other_block_.valuePtr(), other_block_.valuePtr() + other_inner.size(), 0.0);
    other_lu_.analyse(other_block_);
  }
  cholesky_.analyse(nf, lower_start_, lower_rows_);
  splittable_ = cholesky_.analysed();
}

bool IterationMatrixFactors::same_pattern(const Eigen::SparseMatrix<double>& s) const {
  return s.isCompressed() && outer_.size() == static_cast<size_t>(s.outerSize() + 1) &&
         inner_.size() == static_cast<size_t>(s.nonZeros()) &&
         std::equal(outer_.begin(), outer_.end(), s.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), s.innerIndexPtr());
}

bool IterationMatrixFactors::factorize(const Eigen::SparseMatrix<double>& s) {
  split_ = false;
  if (!same_pattern(s)) return false;
  if (!splittable_) return factorize_whole(s);
  const double* v = s.valuePtr();
  const int nf = static_cast<int>(free_.size());
  // the mass-scaled free block, its two triangles compared and averaged
  bool symmetric = true;
  for (int c = 0; c < nf && symmetric; ++c) {
    const double diagonal_c = mass_[c] * v[source_[2 * diagonal_[c]]];
    for (int e = lower_start_[c]; e < lower_start_[c + 1]; ++e) {
      const int r = lower_rows_[e];
      const int own = source_[2 * e], transposed = source_[2 * e + 1];
      const double a = own >= 0 ? mass_[r] * v[own] : 0.0;
      if (r == c) {
        lower_values_[e] = a;
        symmetric = a > 0.0;
        if (!symmetric) break;
        continue;
      }
      const double b = transposed >= 0 ? mass_[c] * v[transposed] : 0.0;
      const double diagonal_r = mass_[r] * v[source_[2 * diagonal_[r]]];
      symmetric = std::abs(a - b) <= kAsymmetry * std::sqrt(std::abs(diagonal_r * diagonal_c));
      lower_values_[e] = 0.5 * (a + b);
      if (!symmetric) break;
    }
  }
  // from now on this pattern is factorised whole: what made the block unsymmetric or
  // indefinite (a friction contact, a follower force, a softening) does not go away in a step
  if (!symmetric || !cholesky_.factorize(lower_values_.data())) {
    splittable_ = false;
    return factorize_whole(s);
  }
  for (size_t k = 0; k < coupling_source_.size(); ++k) coupling_values_[k] = v[coupling_source_[k]];
  if (!other_.empty()) {
    double* block = other_block_.valuePtr();
    for (size_t k = 0; k < other_source_.size(); ++k) block[k] = v[other_source_[k]];
    if (!other_lu_.factorize(other_block_)) return false;  // S_CC singular: so is S
  }
  split_ = true;
  return true;
}

bool IterationMatrixFactors::factorize_whole(const Eigen::SparseMatrix<double>& s) {
  if (!whole_analysed_) {
    whole_lu_.analyse(s);
    whole_analysed_ = true;
  }
  return whole_lu_.factorize(s);
}

Eigen::VectorXd IterationMatrixFactors::solve(const Eigen::VectorXd& b) const {
  if (!split_) return whole_lu_.solve(b);
  Eigen::VectorXd x(n_);
  const int nf = static_cast<int>(free_.size()), nc = static_cast<int>(other_.size());
  // the other coordinates first: their rows read only their own columns
  Eigen::VectorXd x_other;
  if (nc > 0) {
    Eigen::VectorXd b_other(nc);
    for (int c = 0; c < nc; ++c) b_other[c] = b[other_[c]];
    x_other = other_lu_.solve(b_other);
    for (int c = 0; c < nc; ++c) x[other_[c]] = x_other[c];
  }
  // then the free ones: M_F S_FF x_F = M_F (b_F - S_FC x_C)
  Eigen::VectorXd rhs(nf), x_free;
  for (int f = 0; f < nf; ++f) rhs[f] = b[free_[f]];
  for (size_t k = 0; k < coupling_values_.size(); ++k) rhs[coupling_row_[k]] -= coupling_values_[k] * x_other[coupling_col_[k]];
  rhs.array() *= mass_.array();
  cholesky_.solve(rhs, x_free);
  for (int f = 0; f < nf; ++f) x[free_[f]] = x_free[f];
  return x;
}

}  // namespace periflex
