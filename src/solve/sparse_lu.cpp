#include "solve/sparse_lu.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <iterator>
#include <utility>

#include "core/sparsity_pattern.h"

namespace periflex {

namespace {

// The pattern of A + A^T: compressed columns, rows ascending.
void symmetric_pattern(int n, const int* outer, const int* inner, std::vector<int>& start, std::vector<int>& rows) {
  // A^T by counting: scanning the columns in order leaves each of its columns ascending
  std::vector<int> t_start(static_cast<size_t>(n) + 1, 0);
  for (int k = 0; k < outer[n]; ++k) ++t_start[inner[k] + 1];
  for (int i = 0; i < n; ++i) t_start[i + 1] += t_start[i];
  std::vector<int> t_rows(static_cast<size_t>(outer[n]));
  std::vector<int> fill(t_start.begin(), t_start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) t_rows[fill[inner[k]]++] = j;
  start.assign(1, 0);
  rows.clear();
  rows.reserve(static_cast<size_t>(outer[n]) + 16);
  for (int j = 0; j < n; ++j) {
    std::set_union(inner + outer[j], inner + outer[j + 1], t_rows.begin() + t_start[j], t_rows.begin() + t_start[j + 1],
                   std::back_inserter(rows));
    start.push_back(static_cast<int>(rows.size()));
  }
}

// Approximate minimum degree on the pattern of A + A^T, with the unknowns of identical columns
// there (a particle's x and y) ordered as one and kept together: on the notched plate's matrix
// the graph ordered has a quarter of the edges, and the ordering takes 10 against 18-21 ms.
// Returns each unknown's place in the order.
std::vector<int> minimum_degree_positions(int n, const int* outer, const int* inner) {
  std::vector<int> start, rows;
  symmetric_pattern(n, outer, inner, start, rows);
  const std::vector<int> run_start = identical_runs(start, rows);
  const std::vector<int> run = run_of(run_start);
  const int runs = static_cast<int>(run_start.size()) - 1;
  // the graph of the runs: a run meets the runs of its first column's rows
  std::vector<Eigen::Triplet<double, int>> edges;
  edges.reserve(rows.size() / 2);
  for (int g = 0; g < runs; ++g) {
    const int j = run_start[g];
    int last = -1;
    for (int k = start[j]; k < start[j + 1]; ++k)
      if (run[rows[k]] != last) edges.emplace_back(last = run[rows[k]], g, 1.0);
  }
  Eigen::SparseMatrix<double> graph(runs, runs);
  graph.setFromTriplets(edges.begin(), edges.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int> amd;
  amd(graph, order);
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse = order.inverse();
  // the runs in their order, each run's unknowns in theirs
  std::vector<int> run_at(static_cast<size_t>(runs));
  for (int g = 0; g < runs; ++g) run_at[inverse.indices()[g]] = g;
  std::vector<int> position(static_cast<size_t>(n));
  int place = 0;
  for (int g : run_at)
    for (int j = run_start[g]; j < run_start[g + 1]; ++j) position[j] = place++;
  return position;
}

}  // namespace

void SparseLu::analyse(const Eigen::SparseMatrix<double>& a) {
  const int n = static_cast<int>(a.cols());
  const int nnz = static_cast<int>(a.nonZeros());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  outer_.assign(outer, outer + n + 1);
  inner_.assign(inner, inner + nnz);
  position_ = minimum_degree_positions(n, outer, inner);

  // P^T A P built by two counting passes, remembering where each entry of A lands (8 ms on the
  // plate's matrix; Eigen's permutation product takes 34): the entries by permuted row, in the
  // order of their permuted columns, then back into permuted columns in the order of their rows
  std::vector<int> column_at(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) column_at[position_[j]] = j;
  std::vector<int> row_start(static_cast<size_t>(n) + 1, 0);
  for (int k = 0; k < nnz; ++k) ++row_start[position_[inner[k]] + 1];
  for (int i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
  std::vector<int> by_row(static_cast<size_t>(nnz));  // entries of A, by permuted row
  std::vector<int> fill(row_start.begin(), row_start.end() - 1);
  for (int c = 0; c < n; ++c) {
    const int j = column_at[c];
    for (int k = outer[j]; k < outer[j + 1]; ++k) by_row[fill[position_[inner[k]]]++] = k;
  }
  std::vector<int> entry_column(static_cast<size_t>(nnz));  // permuted column of each entry of A
  for (int j = 0; j < n; ++j) std::fill(entry_column.begin() + outer[j], entry_column.begin() + outer[j + 1], position_[j]);
  permuted_.resize(n, n);
  permuted_.resizeNonZeros(nnz);
  int* permuted_outer = permuted_.outerIndexPtr();
  permuted_outer[0] = 0;
  for (int j = 0; j < n; ++j) permuted_outer[position_[j] + 1] = outer[j + 1] - outer[j];
  for (int j = 0; j < n; ++j) permuted_outer[j + 1] += permuted_outer[j];
  permuted_index_.assign(nnz, 0);
  fill.assign(permuted_outer, permuted_outer + n);
  for (int r = 0; r < n; ++r)
    for (int m = row_start[r]; m < row_start[r + 1]; ++m) {
      const int k = by_row[m];
      const int slot = fill[entry_column[k]]++;
      permuted_.innerIndexPtr()[slot] = r;
      permuted_.valuePtr()[slot] = a.valuePtr()[k];
      permuted_index_[k] = slot;
    }
  lu_ = std::make_unique<SymmetricLu>();
  lu_->setPivotThreshold(kDiagonalPivotThreshold);
  lu_->analyzePattern(permuted_);
}

bool SparseLu::same_pattern(const Eigen::SparseMatrix<double>& a) const {
  const int nnz = static_cast<int>(a.nonZeros());
  return a.isCompressed() && outer_.size() == static_cast<size_t>(a.outerSize() + 1) &&
         inner_.size() == static_cast<size_t>(nnz) && std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
}

bool SparseLu::factorize(const Eigen::SparseMatrix<double>& a) {
  if (!lu_) return false;
  if (!same_pattern(a)) return false;  // its values would land in the wrong places
  const double* values = a.valuePtr();
  double* permuted = permuted_.valuePtr();
  for (size_t k = 0; k < permuted_index_.size(); ++k) permuted[permuted_index_[k]] = values[k];
  lu_->factorize(permuted_);
  return lu_->info() == Eigen::Success;
}

long SparseLu::factor_entries() const { return lu_ ? lu_->nnzL() + lu_->nnzU() : 0; }

Eigen::VectorXd SparseLu::solve(const Eigen::VectorXd& b) const {
  const Eigen::Index n = b.size();
  Eigen::VectorXd permuted_b(n);
  for (Eigen::Index i = 0; i < n; ++i) permuted_b[position_[i]] = b[i];
  const Eigen::VectorXd y = lu_->solve(permuted_b);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = y[position_[i]];
  return x;
}

}  // namespace periflex
