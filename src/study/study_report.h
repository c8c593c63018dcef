// Writes what a study measured: study.csv (one row per run), study.md (the same as a Markdown
// table with the observed orders), and study.png, a log-log plot of error against run time drawn
// by gnuplot when it is installed (study.gp, the script, is always written beside it); time
// studies also get energy.csv / energy.gp / energy.png (energy_trace.h).
#pragma once

#include <string>

#include "study/study_result.h"

namespace periflex {

// The columns of study.csv, in order, for time studies and for refine studies.
const std::vector<std::string>& study_csv_columns();
const std::vector<std::string>& refine_csv_columns();

std::string study_csv(const StudyResult& result);
std::string study_markdown(const StudyResult& result);
// One row of the guidance table: "| study | fastest run to 1e-3 | fastest run to 1e-6 |" (relative
// error; written to guidance.md beside study.md).
std::string study_guidance_row(const StudyResult& result);
// The gnuplot script drawing `png_path` from `csv_path`.
std::string study_gnuplot_script(const StudyResult& result, const std::string& csv_path,
                                 const std::string& png_path);

struct StudyOutputs {
  std::string csv_path, markdown_path, plot_path;  // plot_path empty when no plot was made
  std::string plot_message;                        // why there is no plot, when there is none
  std::string energy_plot_path;  // time studies: energy.png (energy error against time), when drawn
};

// Writes the three files into `out_dir` (created when missing). Throws std::runtime_error when a
// file cannot be written; a missing gnuplot is not an error and is reported in plot_message.
StudyOutputs write_study_outputs(const StudyResult& result, const std::string& out_dir);

// True when a `gnuplot` program is on the PATH.
bool gnuplot_available();

}  // namespace periflex
