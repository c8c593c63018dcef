// Runs stability cases through the periflex program (one child process each, with a time and a
// memory limit), checks what each left behind, and writes the table of results.
//
//   SuiteOptions o;  o.program = "/path/to/periflex";  o.out_dir = "out/stability";
//   CaseResult r = run_stability_case(stability_cases()[0], o);
//   write_stability_table(results, "out/stability");   // stability.md + stability.csv
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "stability/stability_case.h"

namespace periflex {

struct SuiteOptions {
  std::string program;          // the periflex executable to run
  std::string out_dir = "out/stability";  // one sub-directory per case
  std::string resource_root;    // where scenes/ is; empty: find_resource_root()
  int threads = 1;              // OMP_NUM_THREADS of each case (the suite runs on shared machines)
  double memory_bytes = 4e9;    // address-space limit of each case
  // a signal the suite received, passed on to the case under way (ChildLimits::interrupt)
  std::function<int()> interrupt;
};

// How a case ended, what it measured, and whether that is what the case expects.
struct CaseResult {
  std::string name, group, description;
  std::string expected;         // expectation_name
  // stable | stopped | refused | warned | crashed | hung | error | skipped
  std::string outcome;
  bool as_expected = false;
  std::string verdict;          // why it is (not) as expected
  int exit_code = -1;
  int signal = 0;
  double run_seconds = 0.0;
  double dt = 0.0;              // the step used when chosen from the critical step
  double critical_time_step = 0.0;
  long steps = 0, rows = 0;
  double simulated_time = 0.0;
  double relative_energy_error = 0.0, energy_error = 0.0;
  double max_violation = 0.0;
  double energy_drift_rate = 0.0, violation_drift_rate = 0.0;  // long runs: per second
  std::string message;          // the diagnostic of a stopped / refused case, or the warning found
  std::vector<std::string> output_problems;  // invalid outputs
};

// Runs one case; never throws for anything the case does (a crash or a hang is an outcome).
CaseResult run_stability_case(const StabilityCase& c, const SuiteOptions& options);

// stability.md (Markdown table plus the messages) and stability.csv in `dir`.
void write_stability_table(const std::vector<CaseResult>& results, const std::string& dir, const std::string& title);

// The Markdown table alone.
std::string stability_table_markdown(const std::vector<CaseResult>& results);

}  // namespace periflex
