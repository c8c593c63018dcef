// `periflex study STUDY.toml`: error against run time for every method a study file names.
// Writes study.csv, study.md and (with gnuplot) study.png into the output folder.
#pragma once

#include <string>

namespace periflex {

struct StudyOptions {
  std::string study_path;     // the study file (TOML)
  std::string out_dir;        // default out/study-<study name>
  int repeats = 0;            // > 0 overrides the study's repeats
  bool quiet = false;         // only the final lines
};

// Runs the study. Returns the process exit code (0 ok, 2 bad input, 3 numerical failure of the
// reference, 1 other). Runs of the grid that fail numerically are rows of the table, not errors.
int study_command(const StudyOptions& options);

}  // namespace periflex
