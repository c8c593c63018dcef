// periflex: flexible multibody dynamics with peridynamic fracture, in 2D.
//
//   periflex                       default scene: the GUI with a display, a recording without
//   periflex run SCENE [...]       headless run: series.csv, summary.json, frames, movies
//   periflex check SCENE           validate and describe a scene
//   periflex gui [SCENE] [...]     interactive visualiser
//   periflex play DIR [...]        the visualiser on a checkpoint folder or VTK series, without simulating
//   periflex study STUDY.toml      error against run time across integrators and steps
//   periflex sweep SWEEP.toml      a grid of scene values, run locally or as a job list
//   periflex stability [--quick]   the stiff and extreme cases, with a table of outcomes
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "cli/check_command.h"
#include "cli/device_option.h"
#include "cli/gui_command.h"
#include "cli/run_command.h"
#include "cli/scene_setup.h"
#include "cli/stability_command.h"
#include "cli/study_command.h"
#include "cli/sweep_command.h"
#include "core/error.h"
#include "core/resources.h"
#include "study/study_def.h"
#include "study/sweep_def.h"

namespace {

using namespace periflex;

bool display_available() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

// A count of steps or frames: a whole number >= 0. (CLI11's NonNegativeNumber names its upper
// bound, the largest double, in 300 digits.)
std::string count_check(const std::string& text) {
  size_t used = 0;
  long long value = -1;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < 0) return "expected a whole number >= 0, found '" + text + "'";
  return {};
}
const CLI::Validator kCount(count_check, "N");

// The subcommands whose work lives in their own files (study, sweep, stability): their options
// here, with the rest of the command line, so that only this file compiles CLI11.
CLI::App* add_study_subcommand(CLI::App& app, StudyOptions& o) {
  auto* cmd = app.add_subcommand("study", "Error against run time for every method a study file names: "
                                          "study.csv, study.md, study.png");
  cmd->add_option("study", o.study_path, "Study file (TOML), e.g. scenes/studies/pendulum.toml")->required();
  cmd->add_option("--out", o.out_dir, "Output directory (default out/study-<name>)");
  cmd->add_option("--repeats", o.repeats, "Timed repeats per run (overrides the study's repeats)")
      ->check(CLI::Range(1, kMaxStudyRepeats));
  cmd->add_flag("--quiet", o.quiet, "Print only where the results went");
  return cmd;
}

CLI::App* add_sweep_subcommand(CLI::App& app, SweepOptions& o) {
  auto* cmd = app.add_subcommand("sweep", "Runs a grid of scene values (a sweep file), or gathers one: sweep.csv");
  cmd->add_option("sweep", o.sweep_path, "Sweep file (TOML), e.g. scenes/studies/notched_plate_sweep.toml");
  cmd->add_option("--out", o.out_dir, "Output directory (default out/sweep-<name>)");
  cmd->add_option("--jobs", o.jobs, "Runs at once on this machine (overrides the sweep's jobs)")
      ->check(CLI::Range(1, kMaxSweepJobs));
  cmd->add_option("--jobs-file", o.jobs_file,
                  "Write one command line per run here (GNU parallel) and sweep.slurm beside the runs; run nothing");
  cmd->add_option("--collect", o.collect_dir, "Gather the runs of this sweep folder into sweep.csv");
  cmd->add_option("--device", o.device, "Where every run's bond forces run: cpu or gpu (overrides solver.device)")
      ->check(CLI::IsMember({"cpu", "gpu"}));
  cmd->add_flag("--quiet", o.quiet, "Print only failed runs and where the results went");
  return cmd;
}

CLI::App* add_stability_subcommand(CLI::App& app, StabilityOptions& o) {
  auto* command = app.add_subcommand(
      "stability", "Run the numerical stability suite: stiff, extreme and long cases; writes a table");
  command->add_flag("--quick", o.quick, "Only the fast cases (a few minutes; the ones ctest runs)");
  command->add_option("--out", o.out_dir, "Output directory (default out/stability)");
  command->add_option("--case", o.cases, "Run only cases whose name contains this text (repeatable)");
  command->add_flag("--list", o.list, "List the cases and exit");
  command->add_option("--threads", o.threads, "OpenMP threads of each case (default 1)")->check(CLI::Range(1, 1024));
  command->add_option("--program", o.program, "The periflex executable each case runs (default: this one)");
  return command;
}

void add_scene_options(CLI::App* command, std::vector<std::string>& overrides) {
  command->add_option("--set", overrides, "Override a scene value, e.g. --set solver.dt=1e-4 (repeatable)")
      ->type_name("KEY=VALUE");
  // the same as --set solver.allow_unstable=true, in its place among the overrides
  command->add_flag_callback(
      "--allow-unstable", [&overrides] { overrides.push_back("solver.allow_unstable=true"); },
      "Run an explicit step above the stable limit instead of refusing it (to watch it diverge: "
      "the run ends with the numerical-failure diagnostic, exit 3)");
}

// The deformation magnification of `run --render` and `gui`.
void add_deform_option(CLI::App* command, std::string& deform) {
  command->add_option("--deform", deform,
                      "Magnify the flexible bodies' deformation K times (0: undeformed; default auto: "
                      "up to 1000x, so the largest deformation shows at a tenth of the body's size)")
      ->type_name("K|auto")
      ->check(CLI::Validator(parse_deform_check, "K|auto"));
}

// Off-screen rendering options shared by `run` and the default headless recording.
void add_render_options(CLI::App* command, RunOptions& o) {
  command->add_flag("--render", o.render, "Render frames off-screen (EGL) while running");
  command->add_option("--frame-every", o.frame_every, "Simulated seconds between frames (default: end time / 100, rounded down to whole steps; at least one step)");
  command->add_option("--size", o.size_text, "Frame size as WxH (default 1280x720)")->type_name("WxH");
  command->add_option("--samples", o.samples,
                      "Multisamples per pixel, 1 = off (default: 4, or off for 100k particles and more)")
      ->check(CLI::Range(1, 16));
  command->add_option("--frames", o.frames_dir, "Directory for the PNG frames");
  command->add_option("--movie", o.movie_path,
                      "Movie written through ffmpeg, its format by the extension: .mp4 (H.264), .webm (VP9), "
                      ".mkv (H.264), .gif, .avi (MPEG-4)");
  command->add_option("--fps", o.fps, "Playback frame rate of the movie")->check(CLI::Range(1.0, 240.0));
  command->add_option("--snapshot-at", o.snapshot_at, "Simulated time of a single screenshot");
  command->add_option("--screenshot", o.screenshot_path, "PNG file for --snapshot-at");
  command->add_option("--colormap", o.colormap, "Colour map: ember (default), grey, turbo, viridis (assets/colormaps)");
  command->add_option("--field", o.field, "Particle colour: damage, displacement, speed, strain");
  command->add_option("--camera", o.camera,
                      "View of the frames: grow (fit the first frame, widen when the scene leaves it; "
                      "default), fit (fit the first frame and keep it), or X,Y,HEIGHT (fixed, metres)");
  add_deform_option(command, o.deform);
  command->add_flag("--draw-contacts", o.draw_contacts, "Draw the active contacts (a dot and a stroke along the force)");
  command->add_option("--plot", o.plot,
                      "Draw a plot of series.csv columns over the frames, at the top right: Y or Y1+Y2+...")
      ->type_name("Y[+Y...]");
  command->add_option("--plot-against", o.plot_against, "The plot's x column (default t)")->type_name("X");
}

int run_main(int argc, char** argv) {
  const GpuBackendInstallation gpu_backend;
  CLI::App app{"periflex: flexible multibody dynamics with peridynamic fracture, in 2D"};
  // the version, and where the program found its shaders, colour maps and scenes
  app.set_version_flag("--version", std::string("periflex ") + PERIFLEX_VERSION + "\nfiles: " + find_resource_root());
  app.require_subcommand(0, 1);

  RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "Run a scene headless: series.csv, summary.json, frames, movies");
  run_cmd->add_option("scene", run.scene_path, "Scene file (TOML)")->required();
  add_scene_options(run_cmd, run.overrides);
  run_cmd->add_option("--until", run.until, "End time (overrides solver.end_time)");
  run_cmd->add_option("--dt", run.dt, "Time step (overrides solver.dt)");
  run_cmd->add_option("--integrator", run.integrator, "Integrator (overrides solver.integrator)");
  run_cmd->add_option("--out", run.out_dir, "Output directory (default out/<scene-name>)");
  run_cmd->add_option("--threads", run.threads, "Threads for the force evaluation (default: all cores)")
      ->check(CLI::Range(0, 1024));
  run_cmd->add_option("--device", run.device,
                      "Where the flexible bodies' bond forces run: cpu or gpu (overrides solver.device, default cpu)")
      ->check(CLI::IsMember({"cpu", "gpu"}));
  run_cmd->add_flag("--quiet", run.quiet, "No progress bar; only the final line");
  run_cmd->add_option("--vtk-every", run.vtk_every, "Write VTK snapshots (particles and rigid bodies, for ParaView) every N steps")
      ->check(kCount);
  run_cmd->add_option("--points-out", run.points_out,
                      "Write the flexible bodies' particles as a point file (x, y, volume, block, no_fail), "
                      "readable by shape = { type = \"points\" }");
  run_cmd->add_option("--checkpoint-every", run.checkpoint_every,
                      "Write the whole state every T simulated seconds (at exact multiples of T)");
  run_cmd->add_option("--checkpoint-dir", run.checkpoint_dir, "Folder of the checkpoints (default <out>/checkpoints)");
  run_cmd->add_option("--restart", run.restart_path,
                      "Continue from a checkpoint file of this scene (same --set overrides; --until may change)");
  add_render_options(run_cmd, run);

  std::string check_scene;
  std::vector<std::string> check_overrides;
  auto* check_cmd = app.add_subcommand("check", "Validate a scene and print what the model contains");
  check_cmd->add_option("scene", check_scene, "Scene file (TOML)")->required();
  add_scene_options(check_cmd, check_overrides);

  GuiCommandOptions gui;
  auto* gui_cmd = app.add_subcommand("gui", "Open the interactive visualiser");
  gui_cmd->add_option("scene", gui.scene_path, "Scene file (default: the notched plate)");
  add_scene_options(gui_cmd, gui.overrides);
  gui_cmd->add_option("--frames", gui.frames, "Draw this many frames, then exit (for scripted runs)")
      ->check(kCount);
  gui_cmd->add_option("--screenshot", gui.screenshot, "Write the last frame to this PNG");
  gui_cmd->add_option("--script", gui.script, "Timed actions, e.g. 'pause@5; step@6; resume@8'");
  gui_cmd->add_option("--samples", gui.samples,
                      "Multisamples of the window, 1 = off (default: 4, or off for 100k particles and more)")
      ->check(CLI::Range(1, 16));
  gui_cmd->add_option("--size", gui.size, "Window size WxH in screen pixels (default 1280x800, at least 640x480)")
      ->check(CLI::Validator(parse_window_size_check, "WxH"));
  add_deform_option(gui_cmd, gui.deform);
  gui_cmd->add_option("--device", gui.device,
                      "Where the flexible bodies' bond forces run: cpu or gpu (overrides solver.device)")
      ->check(CLI::IsMember({"cpu", "gpu"}));

  GuiCommandOptions play;
  auto* play_cmd = app.add_subcommand("play", "Open the visualiser on a checkpoint folder (or a run's VTK series) and move through its states");
  play_cmd->add_option("folder", play.playback_dir, "Checkpoint folder (run --checkpoint-every) or VTK series folder (run --vtk-every)")->required();
  play_cmd->add_option("--frames", play.frames, "Draw this many frames, then exit (for scripted runs)")
      ->check(kCount);
  play_cmd->add_option("--screenshot", play.screenshot, "Write the last frame to this PNG");
  play_cmd->add_option("--script", play.script, "Timed actions, e.g. 'step@2; step@3'");
  play_cmd->add_option("--samples", play.samples, "Multisamples of the window, 1 = off")->check(CLI::Range(1, 16));
  play_cmd->add_option("--size", play.size, "Window size WxH in screen pixels (default 1280x800, at least 640x480)")
      ->check(CLI::Validator(parse_window_size_check, "WxH"));
  add_deform_option(play_cmd, play.deform);

  StudyOptions study;
  auto* study_cmd = add_study_subcommand(app, study);
  SweepOptions sweep;
  auto* sweep_cmd = add_sweep_subcommand(app, sweep);
  StabilityOptions stability;
  auto* stability_cmd = add_stability_subcommand(app, stability);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  if (*run_cmd) return run_command(run);
  if (*check_cmd) return check_command(check_scene, check_overrides);
  if (*study_cmd) return study_command(study);
  if (*sweep_cmd) return sweep_command(sweep);
  if (*stability_cmd) return stability_command(stability);
  if (*play_cmd) return gui_command(play);
  if (*gui_cmd) {
    if (gui.scene_path.empty()) gui.scene_path = default_scene_path();
    return gui_command(gui);
  }

  // No subcommand: the default scene, in a window when there is a display, recorded otherwise.
  if (display_available() && gui_available()) {
    GuiCommandOptions defaults;
    defaults.scene_path = default_scene_path();
    return gui_command(defaults);
  }
  RunOptions record;
  record.scene_path = default_scene_path();
  record.render = render_available();
  record.movie_in_out_dir = record.render && ffmpeg_available();
  return run_command(record);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_main(argc, argv);
  } catch (const periflex::InputError& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return periflex::kExitBadInput;
  } catch (const periflex::NumericalError& error) {
    std::fprintf(stderr, "periflex: numerical failure: %s\n", error.what());
    return periflex::kExitNumerical;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return periflex::kExitOther;
  }
}
