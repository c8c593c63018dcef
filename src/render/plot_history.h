// Time series for the plots, one row per snapshot the render thread sees: every column of
// series.csv the snapshot carries (output/series_row.h), plus the solver's steps/s. Bounded:
// when full, the older half is thinned to every second row, so a long run keeps its whole
// history at a coarser spacing. No GL.
#pragma once

#include <string>
#include <vector>

#include "solve/snapshot.h"

namespace periflex {

class PlotHistory {
 public:
  explicit PlotHistory(size_t capacity = 2000) : capacity_(capacity) {}

  // Appends the row of a snapshot (once per simulation step it shows). A snapshot without a
  // series row gives the columns the snapshot itself holds (time, energies, violation, damage).
  // Other columns than those held start a new history.
  void add(const Snapshot& s, double steps_per_second);
  // Appends a row of `names` (series.csv's columns, "t" first) taken at simulation step `step`,
  // as add does with a snapshot's row; a row of the step added last is left out.
  void add_row(const std::vector<std::string>& names, const std::vector<double>& row, long step,
               double steps_per_second);
  void clear();
  // Forgets the rows at time `t` and after (the window went back in its history to the state at
  // `t`: its row comes next, the later ones are recomputed).
  void drop_from(double t);

  // column names, "t" first and "steps_per_second" last
  const std::vector<std::string>& columns() const { return names_; }
  // the index of a column, -1 when there is none of that name
  int index_of(const std::string& name) const;
  const std::vector<double>& values(int column) const { return columns_[column]; }
  size_t size() const { return columns_.empty() ? 0 : columns_[0].size(); }
  double first_time() const { return size() ? columns_[0].front() : 0.0; }
  double last_time() const { return size() ? columns_[0].back() : 0.0; }

 private:
  void thin();

  size_t capacity_;
  long last_step_ = -1;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
  std::vector<double> row_;
};

}  // namespace periflex
