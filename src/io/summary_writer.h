// summary.json: what ran, how long it took, what the model contained, how it ended.
// Rewritten atomically, so it is valid JSON at every moment of a run; on a full disk, where
// there is no room for a second file, overwritten where it stands.
#pragma once

#include <string>
#include <vector>

#include "solve/simulation.h"

namespace periflex {

struct RunSummary {
  std::string scene;
  std::string scene_path;
  std::vector<std::string> overrides;  // --set values in order (what replaying the run's VTK series loads)
  std::string integrator;
  std::string device = "cpu";     // where the bond forces ran: cpu | gpu (--device, solver.device)
  std::string precision = "fp64"; // their arithmetic: fp64 | fp32 (solver.precision, GPU only)
  std::string device_description; // the GPU's driver and renderer; empty on the CPU
  double dt = 0.0;
  long steps = 0;                 // step count at the end (counted from t = 0)
  long first_step = 0;            // step count the run started from (a restart: the checkpoint's)
  std::string restarted_from;     // the checkpoint file of a restart; empty otherwise
  double simulated_time = 0.0;
  double wall_time = 0.0;         // seconds, solver and output
  double solver_time = 0.0;       // wall seconds in stepping
  double solver_cpu_time = 0.0;   // processor seconds of the solver's threads while stepping
  std::string status = "running"; // running | ok | interrupted | numerical_failure | bad_input | error
  int exit_code = 0;
  std::string message;
  long rows_written = 0;
  long frames_written = 0;
  double render_time = 0.0;
};

// Steps this run took per second of the solver's wall time: the figure the closing line prints too.
double steps_per_second(const RunSummary& run);

// Writes summary.json for `info` and `run` to `path` (atomically).
void write_summary(const std::string& path, const ModelInfo& info, const RunSummary& run);

}  // namespace periflex
