// The structure of a sparse Jacobian: which rows each column can change. Built from pairs
// (row, column) added in any order, repeats allowed, then finished into compressed columns
// (sorted, unique rows per column) in time linear in the pairs added.
//
// The solver uses it for d qdd / d(q, qd): the force elements add the pairs their forces
// couple, the stepper adds what the constraint solve couples, and an implicit integrator
// colours the columns of the result for finite differences (integrator_hht.cpp).
#pragma once

#include <cstdint>
#include <vector>

namespace periflex {

class SparsityPattern {
 public:
  // An empty pattern over size columns and rows.
  void reset(int size);
  int size() const { return size_; }

  // Column `col` can change row `row`.
  void add(int row, int col) { pairs_.push_back({row, col}); }
  // Every column of cols can change every row of rows (ground entries, < 0, are skipped).
  void add_block(const std::vector<int>& rows, const std::vector<int>& cols);

  // Sorts the pairs into columns and adds the diagonal. Call once after the last add.
  void finish();
  // Rows of column j, after finish(): rows()[start()[j] .. start()[j + 1]).
  const std::vector<int>& start() const { return start_; }
  const std::vector<int>& rows() const { return rows_; }
  int64_t nonzeros() const { return static_cast<int64_t>(rows_.size()); }

  bool operator==(const SparsityPattern& other) const {
    return size_ == other.size_ && start_ == other.start_ && rows_ == other.rows_;
  }

 private:
  struct Pair {
    int row, col;
  };
  int size_ = 0;
  std::vector<Pair> pairs_;
  std::vector<int> start_, rows_;
};

// Runs of consecutive lists of a compressed layout (list j: entries[start[j] .. start[j + 1]))
// with the same entries, such as a particle's x and y columns: group_start[g] is the first list
// of run g, group_start.back() the count of lists. Empty lists stay runs of one.
std::vector<int> identical_runs(const std::vector<int>& start, const std::vector<int>& entries);
// For each list, its run.
std::vector<int> run_of(const std::vector<int>& group_start);

// Greedy colouring of the columns so that no two columns of one colour share a row (Curtis,
// Powell & Reid 1974): column j takes the first colour none of whose columns meets one of its
// rows. Returns the columns of each colour, in increasing order. Cost: the sum over columns of
// the column lengths of the rows they meet, linear in the size for a bounded neighbourhood.
std::vector<std::vector<int>> colour_columns(const SparsityPattern& pattern);

}  // namespace periflex
