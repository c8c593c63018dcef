// The energy error of a time study against time: energy.csv (a column per run: |energy
// balance| / largest kinetic energy at each comparison time) and energy.gp, the gnuplot script
// of energy.png, one line per (integrator, correction) series at its largest step or loosest
// tolerance, where drift or its absence shows most. Bounded oscillation is what a symplectic
// integrator promises; steady growth is drift.
#pragma once

#include <string>

#include "study/study_result.h"

namespace periflex {

// "t,<label of run 1>,<label of run 2>,..." then one row per comparison time.
std::string energy_trace_csv(const StudyResult& result);
// The gnuplot script drawing `png_path` from `csv_path` (log scale, floored at 1e-16).
std::string energy_trace_gnuplot_script(const StudyResult& result, const std::string& csv_path,
                                        const std::string& png_path);
// Label of a run in energy.csv and on the plot: "rk4 / projection dt 0.01" (or "tol 1e-08").
std::string energy_run_label(const StudyRow& row);

}  // namespace periflex
