#include "io/summary_writer.h"

#include <cmath>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "output/atomic_file.h"

namespace periflex {

// JSON has no NaN or infinity: write null instead so the file stays valid.
static nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double steps_per_second(const RunSummary& run) {
  return run.solver_time > 0 ? static_cast<double>(run.steps - run.first_step) / run.solver_time : 0.0;
}

void write_summary(const std::string& path, const ModelInfo& info, const RunSummary& run) {
  nlohmann::json j;
  j["scene"] = run.scene;
  j["scene_path"] = run.scene_path;
  j["set"] = run.overrides;
  j["integrator"] = run.integrator;
  j["device"] = run.device;
  j["precision"] = run.precision;
  j["device_description"] = run.device_description.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.device_description);
  j["dt"] = finite_or_null(run.dt);
  j["steps"] = run.steps;
  j["first_step"] = run.first_step;
  j["restarted_from"] = run.restarted_from.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.restarted_from);
  j["simulated_time"] = finite_or_null(run.simulated_time);
  j["wall_time"] = finite_or_null(run.wall_time);
  j["solver_time"] = finite_or_null(run.solver_time);
  j["solver_cpu_time"] = finite_or_null(run.solver_cpu_time);
  j["steps_per_second"] = run.solver_time > 0 ? finite_or_null(steps_per_second(run)) : nlohmann::json(nullptr);
  j["rows_written"] = run.rows_written;
  j["frames_written"] = run.frames_written;
  j["render_time"] = finite_or_null(run.render_time);
  j["status"] = run.status;
  j["exit_code"] = run.exit_code;
  j["message"] = run.message;

  nlohmann::json model;
  model["bodies"] = info.bodies;
  model["virtual_bodies"] = info.virtual_bodies;
  model["joints"] = info.joints;
  model["drivers"] = info.drivers;
  model["force_elements"] = info.force_elements;
  model["probes"] = info.probes;
  model["flex_bodies"] = info.flex_bodies;
  model["particles"] = info.particles;
  model["bonds"] = info.bonds;
  model["coordinates"] = info.coordinates;
  model["constraint_equations"] = info.constraint_equations;
  model["redundant_equations"] = info.redundant_equations;
  model["redundant_constraints"] = info.redundant_constraints;
  model["degrees_of_freedom"] = info.degrees_of_freedom;
  model["critical_time_step"] = finite_or_null(info.critical_time_step);
  model["initial_position_correction"] = finite_or_null(info.initial_position_correction);
  model["initial_velocity_correction"] = finite_or_null(info.initial_velocity_correction);
  model["warnings"] = info.warnings;
  j["model"] = model;
  j["active_modules"] = info.active_modules;

  const std::string text = j.dump(2) + "\n";
  try {
    write_file_atomically(path, text);
  } catch (const std::runtime_error&) {
    // A full disk has no room for the temporary, but the summary written when the run started
    // holds its blocks: the run's end is told there, indented if it fits, else on one line.
    if (!overwrite_in_place(path, text) && !overwrite_in_place(path, j.dump() + "\n")) throw;
  }
}

}  // namespace periflex
