// summary.json: what ran, how long it took, what the model contained, how it ended.
// Rewritten atomically, so it is valid JSON at every moment of a run.
#pragma once

#include <string>

#include "solve/simulation.h"

namespace periflex {

struct RunSummary {
  std::string scene;
  std::string scene_path;
  std::string integrator;
  double dt = 0.0;
  long steps = 0;
  double simulated_time = 0.0;
  double wall_time = 0.0;         // seconds, solver and output
  double solver_time = 0.0;       // seconds in Simulation::step
  std::string status = "running"; // running | ok | numerical_failure | error
  int exit_code = 0;
  std::string message;
  long rows_written = 0;
  long frames_written = 0;
  double render_time = 0.0;
};

// Writes summary.json for `info` and `run` to `path` (atomically).
void write_summary(const std::string& path, const ModelInfo& info, const RunSummary& run);

}  // namespace periflex
