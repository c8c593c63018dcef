// `periflex sweep SWEEP.toml`: a grid of values of any scene keys, each combination one run of
// `periflex run` in its own folder. Runs locally, a bounded number at once, each a child
// process with a time and memory limit; or, with --jobs-file, writes the command lines for GNU
// parallel (one per line, `parallel --sshloginfile` spreads them over machines) and a Slurm
// array script beside them. `periflex sweep --collect DIR` gathers every run's summary.json
// and the last values of the chosen series.csv columns into DIR/sweep.csv.
#pragma once

#include <string>

namespace periflex {

struct SweepOptions {
  std::string sweep_path;   // the sweep file (TOML)
  std::string out_dir;      // default out/sweep-<sweep name>
  int jobs = 0;             // > 0 overrides the sweep's jobs
  std::string jobs_file;    // write the command lines here (and sweep.slurm beside the runs) instead of running
  std::string collect_dir;  // gather the runs of this folder into sweep.csv
  bool quiet = false;
  std::string program;      // the program each run starts (`PROGRAM run ...`); empty: this one
  std::string device;       // --device of every run (cpu | gpu); empty: as the scene says
};

// Returns the exit code: 0 every run ok (or the files written), 2 bad input, 1 a run failed.
int sweep_command(const SweepOptions& options);
// The same, with bad input and other errors thrown (InputError, std::exception) rather than
// printed: for callers that report them their own way (the Python module).
int sweep_or_throw(const SweepOptions& options);

}  // namespace periflex
