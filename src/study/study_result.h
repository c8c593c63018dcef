// What a study measured: one row per run of the method grid, plus the reference it was
// measured against. Filled by run_study (study_runner.h), written by study_report.h.
#pragma once

#include <string>
#include <vector>

#include "study/study_def.h"

namespace periflex {

// One run: a method at one step (or tolerance) and correction, against the reference.
struct StudyRow {
  std::string integrator;
  std::string correction;
  double dt = 0.0;                // fixed step, or initial step of an adaptive run
  double tol = 0.0;               // adaptive runs: rtol (0 for fixed steps)
  // Probe position error at the comparison times (IFToMM: largest and RMS over the run) [m], and
  // the same relative to the largest excursion of the reference probes from their start.
  double error_max = 0.0, error_rms = 0.0;
  double error_max_rel = 0.0, error_rms_rel = 0.0;
  // Largest |energy balance| over the run [J], and relative to the largest kinetic energy.
  double energy_error = 0.0, energy_error_rel = 0.0;
  double violation = 0.0;         // largest |Phi| over the run
  double crack_tip_error = 0.0;   // largest |crack length - reference| [m] (flexible scenes with fracture)
  double broken_bond_error = 0.0; // largest |broken bonds - reference| / max(1, reference at the end)
  double wall_time = 0.0;         // median over repeats of the solver's seconds (output excluded)
  long steps = 0;
  std::string status = "ok";      // "ok" or "failed: <what>"
  // |energy balance| at each comparison time (StudyResult::times), relative to the run's largest
  // kinetic energy: how the energy error evolves, drift or bounded (energy.csv, energy.png)
  std::vector<double> energy_trace;
  // Refine studies: the grid, the measured quantity and its known answer (error_max_rel is
  // |measured - expected| / expected there).
  double grid_spacing = 0.0, horizon_ratio = 0.0;
  long particles = 0;
  double measured = 0.0, expected = 0.0;
  bool ok() const { return status == "ok"; }
};

// Observed order of one (integrator, correction) series: slope of log error against log dt
// (or log tol for adaptive runs) by least squares over its successful rows.
struct ObservedOrder {
  std::string integrator, correction;
  bool against_tolerance = false;
  double slope = 0.0;
  int points = 0;
  int theory = 0;                 // order in dt; 1 (tolerance proportionality) against tol
};

struct StudyResult {
  StudyDef study;
  std::string scene_name;
  std::string reference_description;
  // Converged references: its own error, estimated from a run at twice its step [m]; 0 if exact.
  double reference_error = 0.0;
  double reference_wall_time = 0.0;
  double excursion = 0.0;         // the scale of relative errors [m]
  bool has_fracture = false;      // crack-tip and broken-bond columns are meaningful
  std::vector<StudyRow> rows;
  std::vector<double> times;      // the comparison times (time studies)
  std::vector<ObservedOrder> orders;
  std::string quantity;           // refine studies: what was measured (wave_speed, ...)
  std::string quantity_unit;
  // Ended early by the caller's stop (Ctrl-C): rows holds the runs that finished, the rest of the
  // grid did not run.
  bool stopped = false;
};

// Least-squares slope of log(error_max) against log(dt) per series, or against log(tol) for a
// series whose tolerance varies. Rows at the
// round-off floor (relative error below `floor`) are left out, as they measure nothing of the method.
std::vector<ObservedOrder> observed_orders(const std::vector<StudyRow>& rows, double floor = 1e-13);

}  // namespace periflex
