#include "core/sparsity_pattern.h"

#include <algorithm>

namespace periflex {

void SparsityPattern::reset(int size) {
  size_ = size;
  pairs_.clear();
  start_.clear();
  rows_.clear();
}

void SparsityPattern::add_block(const std::vector<int>& rows, const std::vector<int>& cols) {
  for (int c : cols) {
    if (c < 0) continue;
    for (int r : rows)
      if (r >= 0) add(r, c);
  }
}

void SparsityPattern::finish() {
  // the diagonal: every coordinate's acceleration is its own unknown in the iteration matrix
  for (int j = 0; j < size_; ++j) add(j, j);
  // counting sort of the pairs by column, then each column's rows sorted and made unique
  std::vector<int> count(static_cast<size_t>(size_) + 1, 0);
  for (const Pair& p : pairs_) ++count[p.col + 1];
  for (int j = 0; j < size_; ++j) count[j + 1] += count[j];
  std::vector<int> sorted(pairs_.size());
  std::vector<int> next(count.begin(), count.end() - 1);
  for (const Pair& p : pairs_) sorted[next[p.col]++] = p.row;
  pairs_.clear();
  pairs_.shrink_to_fit();
  start_.assign(static_cast<size_t>(size_) + 1, 0);
  rows_.clear();
  rows_.reserve(sorted.size());
  for (int j = 0; j < size_; ++j) {
    const auto first = sorted.begin() + count[j], last = sorted.begin() + count[j + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    rows_.insert(rows_.end(), first, end);
    start_[j + 1] = static_cast<int>(rows_.size());
  }
}

std::vector<std::vector<int>> colour_columns(const SparsityPattern& pattern) {
  const int n = pattern.size();
  const std::vector<int>& start = pattern.start();
  const std::vector<int>& rows = pattern.rows();
  // the transpose: the columns that meet each row
  std::vector<int> row_start(static_cast<size_t>(n) + 1, 0);
  for (int r : rows) ++row_start[r + 1];
  for (int i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
  std::vector<int> row_cols(rows.size());
  std::vector<int> fill(row_start.begin(), row_start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int k = start[j]; k < start[j + 1]; ++k) row_cols[fill[rows[k]]++] = j;

  // first fit in column order: a colour is taken when an earlier column of it shares a row
  std::vector<int> colour(n, -1);
  std::vector<int> taken_by;  // per colour: the last column that found it taken
  std::vector<std::vector<int>> colours;
  for (int j = 0; j < n; ++j) {
    for (int k = start[j]; k < start[j + 1]; ++k) {
      const int i = rows[k];
      // the row's columns are in ascending order: from j on, none is coloured yet
      for (int m = row_start[i]; m < row_start[i + 1] && row_cols[m] < j; ++m) taken_by[colour[row_cols[m]]] = j;
    }
    int c = 0;
    while (c < static_cast<int>(colours.size()) && taken_by[c] == j) ++c;
    if (c == static_cast<int>(colours.size())) {
      colours.emplace_back();
      taken_by.push_back(-1);
    }
    colour[j] = c;
    colours[c].push_back(j);
  }
  return colours;
}

}  // namespace periflex
