// The one check of command-line values for `run` and `gui`, before the scene is built: every
// number finite and in range, names from the real lists (colour maps, fields), output paths
// writable as the folder or file each flag expects, and the scene loaded with the run's plan
// (frames, threads) so that its budget covers them. Errors name the flag and exit 2.
#pragma once

#include <string>
#include <vector>

#include "cli/gui_command.h"
#include "cli/run_command.h"
#include "scene/scene_def.h"

namespace periflex {

// A safe folder name made from a scene name: letters, digits, '.', '-' and '_' only (others
// become '_'), no leading dot, at most 64 characters; "scene" when nothing is left.
std::string safe_folder_name(const std::string& name);

// Colour maps the renderer can load (assets/colormaps/*.png), sorted.
std::vector<std::string> colormap_names();

// The simulated time between frames: --frame-every when given, else the default: the largest
// whole number of steps not above end_time / 100, at least one step (end_time / 100 for the
// adaptive dopri54). The default is never refused.
double frame_interval(const RunOptions& options, const SolverDef& solver);

// Checks the options of `run`, loads and checks the scene with them, fills options.out_dir
// with out/<safe scene name> when it is empty and checks every output path. Throws InputError.
SceneDef load_run_scene(RunOptions& options);

// Checks the options of `run` on a checkpoint folder (cli/playback_render.h), before the folder
// is read: the rendering ones as for a scene, and none of those that shape a simulation. Throws
// InputError naming the flag.
void check_replay_flags(const RunOptions& options);
// Then the output paths; fills options.out_dir with out/<safe scene name>-replay when it is
// empty. Throws InputError naming the flag.
void check_replay_outputs(RunOptions& options, const std::string& scene_name);

// The columns --plot names ("Y1+Y2", split at '+'), each checked against `columns` (the run's
// series.csv columns), and --plot-against likewise. Throws InputError naming the flag and listing
// the columns.
std::vector<std::string> plot_columns_checked(const RunOptions& options, const std::vector<std::string>& columns);

// Checks the options of `gui` and that its scene loads within its budget. Throws InputError.
void check_gui_options(const GuiCommandOptions& options);

}  // namespace periflex
