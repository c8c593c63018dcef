// What a sweep file (TOML) asks for: a scene, a grid of values of any of its keys (the --set
// machinery), and what to gather from each run. `periflex sweep` expands the grid into runs of
// `periflex run` (cli/sweep_command.cpp); docs/running.md documents the keys.
//
//   [sweep]
//   scene = "../notched_plate.toml"       # relative to the sweep file
//   set = ["solver.end_time=2e-4"]        # overrides every run shares
//   jobs = 2                              # runs at once on this machine
//   timeout = 3600                        # seconds a run may take before it is stopped
//   memory_gb = 4                         # address space a run may take
//   series = ["probe.notch_tip.y"]        # last values of series.csv columns to gather
//   [[parameter]]
//   key = "flex_body.plate.material.fracture_energy"
//   values = [150.0, 300.0, 600.0]
#pragma once

#include <string>
#include <vector>

#include "core/error.h"

namespace periflex {

// One axis of the grid: a scene key and the values it takes, as TOML text for --set.
struct SweepParameter {
  std::string key;
  std::vector<std::string> values;
  SourceLocation where;  // the values' position in the sweep file
};

struct SweepDef {
  std::string name;          // default: file stem
  std::string path;          // the sweep file
  std::string scene_path;    // resolved against the sweep file's folder
  std::vector<std::string> overrides;  // "key=value" for every run
  std::vector<SweepParameter> parameters;
  int jobs = 2;
  double timeout_seconds = 3600.0;
  double memory_bytes = 4e9;
  std::vector<std::string> series;  // series.csv columns whose last value is gathered
  SourceLocation series_where;      // the series' position in the sweep file
};

// One run of the grid: its folder name and every override it runs with.
struct SweepRun {
  std::string folder;                 // "run_0001", ...
  std::vector<std::string> values;    // one per parameter, as TOML text
  std::vector<std::string> overrides; // the sweep's, then the parameters'
};

// Parses a sweep; throws InputError naming file, line, column and key.
SweepDef parse_sweep(const std::string& toml_text, const std::string& display_path);
SweepDef load_sweep(const std::string& path);

// Runs a sweep may hold: each is a folder and a scene read before anything runs (about 0.1 ms
// and 1 kB each), and a Slurm array or a job list of more is a mistake more often than a plan.
constexpr double kMaxSweepRuns = 1e5;
// Runs at once (the file's jobs and --jobs alike), and the address space one run may be given.
constexpr int kMaxSweepJobs = 1024;
constexpr double kMaxSweepMemoryGb = 1e6;

// The runs of the grid, the last parameter varying fastest. Each run's scene is loaded once
// with its overrides, so a key or value the scene refuses is reported at the parameter's line
// in the sweep file, and a series column its runs would not write at the series' line
// (InputError).
std::vector<SweepRun> expand_sweep(const SweepDef& sweep);

}  // namespace periflex
