// Reads what `periflex run` leaves behind (series.csv, summary.json) and checks it is intact:
// complete rows, only finite numbers, a valid summary whose status matches the exit code.
// The stability measures of a case (energy error, constraint violation, drift) come from here.
#pragma once

#include <string>
#include <vector>

namespace periflex {

// series.csv, as numbers.
struct Series {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const;  // index, or -1
};

// What was found in an output directory.
struct RunOutputs {
  bool valid = true;               // every check below passed
  std::vector<std::string> problems;  // what did not (a non-finite cell, a short row, bad JSON ...)

  // summary.json
  bool has_summary = false;
  std::string status;              // ok | numerical_failure | running | error
  int summary_exit_code = -1;
  std::string message;
  long steps = 0;
  double simulated_time = 0.0;
  double critical_time_step = 0.0;
  std::vector<std::string> warnings;

  // series.csv
  long rows = 0;
  double last_time = 0.0;
  // Largest |energy_balance| over the rows, and the scale it is measured against: the largest
  // energy any one account reached (kinetic, elastic, dissipated, fracture, work; gravity as its
  // change from the start), so the relative error reads as "fraction of the energy in play".
  double energy_error = 0.0;
  double energy_scale = 0.0;
  double relative_energy_error() const;
  double max_violation = 0.0;      // largest violation_position over the rows
  double final_violation = 0.0;
  // Least-squares slopes over time of energy_balance and of violation_position (per second).
  double energy_drift_rate = 0.0;
  double violation_drift_rate = 0.0;
};

// Parses CSV text; any row whose cell count differs from the header, or any cell that is not a
// finite number, is a problem (reported, and the row is dropped).
Series parse_series(const std::string& text, std::vector<std::string>& problems);

// Reads `dir`/series.csv and `dir`/summary.json and checks them against the process exit code
// (0: status ok and at least one row; 3: status numerical_failure and a message).
RunOutputs read_run_outputs(const std::string& dir, int exit_code);

}  // namespace periflex
