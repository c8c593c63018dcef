#include "render/plot_history.h"

#include <algorithm>

namespace periflex {

namespace {

// the columns a snapshot without a series row holds, named as series.csv names them
const std::vector<std::string>& snapshot_columns() {
  static const std::vector<std::string> names = {
      "t", "kinetic", "potential_gravity", "potential_elastic", "dissipated", "fracture", "external_work",
      "driver_work", "energy_balance", "violation_position", "violation_velocity", "broken_bonds", "max_damage"};
  return names;
}

void snapshot_row(const Snapshot& s, std::vector<double>& row) {
  const Energies& e = s.energies;
  row = {s.time,          e.kinetic,     e.potential_gravity,  e.potential_elastic,  e.dissipated,
         e.fracture,      e.external_work, e.driver_work,      e.balance,            s.violation_position,
         s.violation_velocity, static_cast<double>(s.broken_bonds), s.max_damage};
}

}  // namespace

void PlotHistory::add(const Snapshot& s, double steps_per_second) {
  // this snapshot's columns and row
  const bool has_row = s.series_columns && s.series.size() == s.series_columns->size() && !s.series.empty();
  if (has_row) {
    add_row(*s.series_columns, s.series, s.step, steps_per_second);
  } else {
    std::vector<double> row;
    snapshot_row(s, row);
    add_row(snapshot_columns(), row, s.step, steps_per_second);
  }
}

void PlotHistory::add_row(const std::vector<std::string>& names, const std::vector<double>& row, long step,
                          double steps_per_second) {
  if (step == last_step_ && size() > 0) return;
  last_step_ = step;
  row_ = row;
  row_.push_back(steps_per_second);
  // other columns: a new history
  const bool same = names_.size() == names.size() + 1 && std::equal(names.begin(), names.end(), names_.begin());
  if (!same) {
    names_ = names;
    names_.push_back("steps_per_second");
    columns_.assign(names_.size(), {});
  }
  if (size() >= capacity_) thin();
  for (size_t k = 0; k < columns_.size(); ++k) columns_[k].push_back(row_[k]);
}

void PlotHistory::clear() {
  for (auto& v : columns_) v.clear();
  last_step_ = -1;
}

void PlotHistory::drop_from(double t) {
  if (columns_.empty()) return;
  // the rows are in time order: keep those before t
  const std::vector<double>& time = columns_[0];
  const size_t keep = static_cast<size_t>(std::lower_bound(time.begin(), time.end(), t) - time.begin());
  for (auto& v : columns_) v.resize(keep);
  last_step_ = -1;
}

int PlotHistory::index_of(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  return it == names_.end() ? -1 : static_cast<int>(it - names_.begin());
}

void PlotHistory::thin() {
  // keep every second row of the older half, all of the newer half
  const size_t half = size() / 2;
  for (auto& v : columns_) {
    size_t out = 0;
    for (size_t i = 0; i < half; i += 2) v[out++] = v[i];
    for (size_t i = half; i < v.size(); ++i) v[out++] = v[i];
    v.resize(out);
  }
}

}  // namespace periflex
