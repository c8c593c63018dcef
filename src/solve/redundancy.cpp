#include "solve/redundancy.h"

#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cmath>
#include <utility>

namespace periflex {

namespace {

// Above this many rows the dense QR would cost more than the sparse one, unless the rows span
// few columns (a thin matrix: the QR's cost is rows x columns x rank).
constexpr int kDenseRowLimit = 600;
constexpr double kDenseEntryLimit = 4e6;
// An entry below this fraction of its row's original 1-norm is round-off from an elimination.
constexpr double kNegligible = 1e-13;
// A pivot within this factor of a column's largest (row-relative) entry is good enough.
constexpr double kPivotFactor = 0.1;
// A dependency whose right-hand sides differ by more than this fraction of their size conflicts.
constexpr double kConflict = 1e-8;

using Entry = std::pair<int, double>;  // column, value; kept sorted by column

// One row while the columns are eliminated: its entries, its right-hand side, and the pivot
// rows subtracted from it (to name the rows of a conflicting dependency).
struct WorkRow {
  std::vector<Entry> entries;
  double rhs = 0.0;
  double scale = 0.0;  // original 1-norm
  std::vector<int> history;
};

double value_at(const WorkRow& row, int column) {
  const auto it = std::lower_bound(row.entries.begin(), row.entries.end(), Entry{column, -HUGE_VAL},
                                   [](const Entry& a, const Entry& b) { return a.first < b.first; });
  return it != row.entries.end() && it->first == column ? it->second : 0.0;
}

// row -= f * pivot, with the entry in `column` removed; new columns go to `added`.
void subtract(WorkRow& row, const WorkRow& pivot, double f, int column, std::vector<int>& added,
              std::vector<Entry>& merged) {
  merged.clear();
  size_t a = 0, b = 0;
  const double floor = kNegligible * row.scale;
  while (a < row.entries.size() || b < pivot.entries.size()) {
    int c;
    double v;
    if (b >= pivot.entries.size() || (a < row.entries.size() && row.entries[a].first < pivot.entries[b].first)) {
      c = row.entries[a].first;
      v = row.entries[a++].second;
    } else if (a >= row.entries.size() || pivot.entries[b].first < row.entries[a].first) {
      c = pivot.entries[b].first;
      v = -f * pivot.entries[b++].second;
      added.push_back(c);
    } else {
      c = row.entries[a].first;
      v = row.entries[a++].second - f * pivot.entries[b++].second;
    }
    if (c != column && std::abs(v) > floor) merged.emplace_back(c, v);
  }
  row.entries.swap(merged);
  row.rhs -= f * pivot.rhs;
  row.history.insert(row.history.end(), pivot.history.begin(), pivot.history.end());
}

// Dependent ones among `rows` (all over few columns) by a column-pivoted QR of their transpose;
// with rhs, the rows of every dependency whose right-hand sides disagree go to `conflicting`.
void qr_stage(const std::vector<WorkRow>& work, const std::vector<int>& rows, int n, const RowAnalysisOptions& options,
              RowDependence& out) {
  const int m = static_cast<int>(rows.size());
  if (m == 0) return;
  // the columns the rows use, numbered compactly
  std::vector<int> compact(n, -1), used;
  for (int r : rows) {
    for (const auto& [c, v] : work[r].entries) {
      if (compact[c] < 0) {
        compact[c] = static_cast<int>(used.size());
        used.push_back(c);
      }
    }
  }
  const int nu = static_cast<int>(used.size());
  // rows the elimination emptied: each depends on the others (and conflicts with a right-hand side)
  if (nu == 0) {
    for (int r : rows) {
      out.dependent.push_back(r);
      if (options.rhs && std::abs(work[r].rhs) > 0.0) {
        out.conflicting.push_back(r);
        out.conflicting.insert(out.conflicting.end(), work[r].history.begin(), work[r].history.end());
      }
    }
    std::sort(out.conflicting.begin(), out.conflicting.end());
    out.conflicting.erase(std::unique(out.conflicting.begin(), out.conflicting.end()), out.conflicting.end());
    return;
  }
  // metric: columns by 1/sqrt(w), rows to unit length
  std::vector<double> column_scale(nu, 1.0);
  if (options.column_weight) {
    for (int k = 0; k < nu; ++k) {
      const double w = (*options.column_weight)[used[k]];
      column_scale[k] = w > 0.0 ? 1.0 / std::sqrt(w) : 1.0;
    }
  }
  std::vector<double> row_scale(m, 1.0);
  if (options.column_weight) {
    for (int k = 0; k < m; ++k) {
      double norm2 = 0.0;
      for (const auto& [c, v] : work[rows[k]].entries) norm2 += std::pow(v * column_scale[compact[c]], 2);
      row_scale[k] = norm2 > 0.0 ? 1.0 / std::sqrt(norm2) : 1.0;
    }
  }

  const bool dense = m <= kDenseRowLimit || (nu <= kDenseRowLimit && double(nu) * m <= kDenseEntryLimit);
  if (!dense) {
    Eigen::SparseMatrix<double> jt(nu, m);
    std::vector<Eigen::Triplet<double>> entries;
    for (int k = 0; k < m; ++k) {
      for (const auto& [c, v] : work[rows[k]].entries)
        entries.emplace_back(compact[c], k, v * column_scale[compact[c]] * row_scale[k]);
    }
    jt.setFromTriplets(entries.begin(), entries.end());
    jt.makeCompressed();
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
    double max_norm = 0.0;
    for (int c = 0; c < jt.cols(); ++c) max_norm = std::max(max_norm, jt.col(c).norm());
    qr.setPivotThreshold(options.relative_threshold * max_norm);
    qr.compute(jt);
    const auto& perm = qr.colsPermutation().indices();
    for (int k = static_cast<int>(qr.rank()); k < m; ++k) out.dependent.push_back(rows[perm[k]]);
    return;
  }

  // columns of J^T are the equations; the pivoting order puts independent ones first
  Eigen::MatrixXd jt = Eigen::MatrixXd::Zero(nu, m);
  for (int k = 0; k < m; ++k) {
    for (const auto& [c, v] : work[rows[k]].entries) jt(compact[c], k) = v * column_scale[compact[c]] * row_scale[k];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jt);
  qr.setThreshold(options.relative_threshold);
  const int rank = static_cast<int>(qr.rank());
  const auto& perm = qr.colsPermutation().indices();
  for (int k = rank; k < m; ++k) out.dependent.push_back(rows[perm[k]]);
  if (!options.rhs || rank == m) return;

  // each dependent column d of J^T P = Q [R11 R12] equals the kept ones times R11^-1 R12(:, d);
  // the null vector y = e_d - that combination must give y^T rhs = 0 (in the scaled rows)
  const Eigen::MatrixXd r = qr.matrixR().topRows(rank);
  const Eigen::MatrixXd a =
      r.leftCols(rank).triangularView<Eigen::Upper>().solve(r.rightCols(m - rank));
  auto rhs_of = [&](int k) { return work[rows[k]].rhs * row_scale[k]; };
  std::vector<char> named(work.size(), 0);
  auto name = [&](int k) {
    const WorkRow& row = work[rows[k]];
    named[rows[k]] = 1;
    for (int h : row.history) named[h] = 1;
  };
  // round-off in the combination is relative to the largest right-hand side it could pick up
  double largest_rhs = 0.0;
  for (int k = 0; k < m; ++k) largest_rhs = std::max(largest_rhs, std::abs(rhs_of(k)));
  for (int i = 0; i < m - rank; ++i) {
    const int d = perm[rank + i];
    double mismatch = rhs_of(d);
    for (int k = 0; k < rank; ++k) mismatch -= a(k, i) * rhs_of(perm[k]);
    const double size = largest_rhs * (1.0 + a.col(i).cwiseAbs().sum());
    if (!(std::abs(mismatch) > kConflict * size)) continue;
    name(d);
    const double largest = rank > 0 ? a.col(i).cwiseAbs().maxCoeff() : 0.0;
    for (int k = 0; k < rank; ++k) {
      if (std::abs(a(k, i)) > 1e-6 * largest) name(perm[k]);
    }
  }
  for (size_t row = 0; row < named.size(); ++row) {
    if (named[row]) out.conflicting.push_back(static_cast<int>(row));
  }
}

}  // namespace

RowDependence find_dependent_rows(const Eigen::SparseMatrix<double>& j, const RowAnalysisOptions& options) {
  const int m = static_cast<int>(j.rows());
  const int n = static_cast<int>(j.cols());
  RowDependence out;
  if (m == 0) return out;

  // the rows as sorted entry lists
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = j;
  std::vector<WorkRow> work(m);
  for (int r = 0; r < m; ++r) {
    WorkRow& w = work[r];
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      w.scale += std::abs(it.value());
    }
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      if (std::abs(it.value()) > 1e-12 * w.scale) w.entries.emplace_back(static_cast<int>(it.col()), it.value());
    }
    w.rhs = options.rhs ? (*options.rhs)[r] : 0.0;
  }

  // elimination of the eliminable columns, each by the row holding it most strongly (relative
  // to the row's size); pivot rows are independent
  std::vector<char> is_pivot(m, 0);
  const bool any_eliminable = std::any_of(options.eliminable.begin(), options.eliminable.end(), [](char e) { return e; });
  if (any_eliminable) {
    std::vector<std::vector<int>> holders(n);
    for (int r = 0; r < m; ++r) {
      for (const auto& [c, v] : work[r].entries) {
        if (options.eliminable[c]) holders[c].push_back(r);
      }
    }
    std::vector<int> added;
    std::vector<Entry> merged;
    for (int c = 0; c < n; ++c) {
      if (!options.eliminable[c] || holders[c].empty()) continue;
      // threshold pivoting: the first row (lowest index) within a factor of the largest entry,
      // so a particle's two columns take their pivots from the same joint
      double best = 0.0;
      for (int r : holders[c]) {
        if (!is_pivot[r]) best = std::max(best, std::abs(value_at(work[r], c)) / work[r].scale);
      }
      if (!(best > kNegligible)) continue;
      int pivot = -1;
      for (int r : holders[c]) {
        if (is_pivot[r] || std::abs(value_at(work[r], c)) / work[r].scale < kPivotFactor * best) continue;
        if (pivot < 0 || r < pivot) pivot = r;
      }
      is_pivot[pivot] = 1;
      const double pv = value_at(work[pivot], c);
      for (int r : holders[c]) {
        if (is_pivot[r]) continue;
        const double v = value_at(work[r], c);
        if (v == 0.0) continue;
        added.clear();
        work[r].history.push_back(pivot);
        subtract(work[r], work[pivot], v / pv, c, added, merged);
        // fill-in on columns still to be eliminated
        for (int a : added) {
          if (a > c && options.eliminable[a]) holders[a].push_back(r);
        }
      }
      holders[c].clear();
      holders[c].shrink_to_fit();
    }
  }

  // rows with a column no other remaining row touches cannot take part in a dependency: peel
  // them off (a few passes: peeling one may free another)
  std::vector<char> remaining(m);
  for (int r = 0; r < m; ++r) remaining[r] = !is_pivot[r];
  std::vector<int> column_count(n, 0);
  for (int r = 0; r < m; ++r) {
    if (!remaining[r]) continue;
    for (const auto& [c, v] : work[r].entries) ++column_count[c];
  }
  for (int pass = 0; pass < 4; ++pass) {
    bool peeled = false;
    for (int r = 0; r < m; ++r) {
      if (!remaining[r] || work[r].entries.empty()) continue;
      bool has_private = false;
      for (const auto& [c, v] : work[r].entries) has_private = has_private || column_count[c] == 1;
      if (!has_private) continue;
      remaining[r] = 0;
      peeled = true;
      for (const auto& [c, v] : work[r].entries) --column_count[c];
    }
    if (!peeled) break;
  }

  // the rest, the small system of the bodies, through the rank-revealing QR
  std::vector<int> rest;
  for (int r = 0; r < m; ++r) {
    if (remaining[r]) rest.push_back(r);
  }
  qr_stage(work, rest, n, options, out);
  for (int r = 0; r < m; ++r) {
    if (is_pivot[r]) out.pivots.push_back(r);
  }
  std::sort(out.dependent.begin(), out.dependent.end());
  return out;
}

std::vector<int> dependent_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) {
  RowAnalysisOptions options;
  options.relative_threshold = relative_threshold;
  return find_dependent_rows(j, options).dependent;
}

int column_rank(const Eigen::MatrixXd& j, double relative_threshold) {
  if (j.cols() == 0) return 0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(j);
  qr.setThreshold(relative_threshold);
  return static_cast<int>(qr.rank());
}

}  // namespace periflex
