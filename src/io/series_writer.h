// series.csv: one row per output sample (time, energies, constraint violation, damage, probes).
// Each row reaches the file in one write() call of the whole line (no stdio buffer to split it,
// however many probe columns), so a run killed half-way leaves complete rows; a line that a full
// disk cuts short is taken back out.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "solve/simulation.h"

namespace periflex {

class SeriesWriter {
 public:
  // Opens `path` and writes the header, then `earlier_rows` (whole lines a restarted run keeps,
  // series_rows_before). Damage columns only when the scene has particles, contact columns
  // (contact_force_total, contact_count) only when it declares [[contact]].
  SeriesWriter(const std::string& path, const std::vector<std::string>& probe_columns, bool with_damage,
               bool with_contact = false, const std::string& earlier_rows = "");
  ~SeriesWriter();
  SeriesWriter(const SeriesWriter&) = delete;
  SeriesWriter& operator=(const SeriesWriter&) = delete;

  // Appends a row. Returns false (and writes nothing) if any value is not finite.
  bool write(const Sample& sample);
  long rows() const { return rows_; }
  // The values of the row written last, in the order of columns().
  const std::vector<double>& last_row() const { return values_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  // Writes all of `text` at the end of the file; throws when the disk refuses, after cutting
  // the file back to its whole lines.
  void write_all(const std::string& text);

  int fd_ = -1;
  off_t size_ = 0;  // bytes of whole lines in the file
  std::string path_;
  std::vector<std::string> columns_;
  bool with_damage_ = false, with_contact_ = false;
  long rows_ = 0;
  std::string line_;
  std::vector<double> values_;
};

// The rows of the series.csv at `path` before `time`, as whole lines, when its header is
// `columns`: what a run restarted into its own folder keeps, so that its series.csv holds the
// whole run. Empty when there is no such file, its header differs (another scene's), or no row
// comes before `time`; a line cut short ends the rows kept.
std::string series_rows_before(const std::string& path, const std::vector<std::string>& columns, double time);

}  // namespace periflex
