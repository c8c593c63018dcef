// `periflex run SCENE ...`: a headless run writing series.csv, summary.json and optional
// VTK snapshots and rendered frames / movies.
#pragma once

#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace periflex {

struct RunOptions {
  std::string scene_path;
  std::vector<std::string> overrides;   // --set key.path=value
  std::optional<double> until;          // end time
  std::optional<double> dt;
  std::optional<std::string> integrator;
  std::string out_dir;                  // default out/<scene-name>
  int threads = 0;                      // 0: all cores
  std::string device;                   // --device: cpu | gpu (cli/device_option.h); empty: solver.device
  std::string device_description;       // the GPU's driver and renderer, filled when it is checked
  bool quiet = false;
  long vtk_every = 0;                   // steps between VTK snapshots; 0: none
  std::string points_out;               // the flexible bodies as a point file; empty: none

  // Checkpoints (output/checkpoint_file.h).
  double checkpoint_every = 0.0;        // simulated seconds between checkpoint files; 0: none
  std::string checkpoint_dir;           // default <out>/checkpoints
  std::string restart_path;             // continue from this checkpoint file

  // Off-screen rendering.
  bool render = false;
  double frame_every = 0.0;             // simulated seconds between frames; 0: end_time / 100
  std::string size_text;                // "WxH"; empty: 1280x720
  int width = 1280, height = 720;       // parsed from size_text by run_command
  int samples = 0;                      // multisamples per pixel; 0: 4, or 1 from 100k particles on
  std::string frames_dir;               // PNG sequence; default <out>/frames when rendering
  std::string movie_path;               // MP4 through ffmpeg
  bool movie_in_out_dir = false;        // movie.mp4 in the output directory (default recording)
  double fps = 30.0;
  std::optional<double> snapshot_at;    // one frame at this time ...
  std::string screenshot_path;          // ... written here
  std::string colormap;                 // empty: default
  std::string field;                    // damage | displacement | speed | strain
  std::string camera;                   // grow (default) | fit | "X,Y,HEIGHT"
  std::string deform;                   // deformation magnification: auto (default) | K >= 0
  bool draw_contacts = false;           // draw the active contacts and their forces
  std::string plot;                     // series.csv columns plotted over the frames: "Y1+Y2"
  std::string plot_against;             // the plot's x column; empty: t
};

// Returns the process exit code (0 ok, 2 bad input, 3 numerical failure, 1 other).
int run_command(const RunOptions& options);

// How a run ended, for callers that report it their own way (the Python module).
struct RunOutcome {
  int exit_code = 0;
  std::string out_dir;            // the folder the outputs went to (the default filled in)
  std::exception_ptr failure;     // the error that stopped the run after it started, if any
};
// The same run. Bad input found before the run starts is thrown, as by run_command.
RunOutcome run_and_report(const RunOptions& options);

}  // namespace periflex
