#include "cli/run_option_checks.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "cli/camera_option.h"
#include "cli/device_option.h"
#include "cli/scene_setup.h"
#include "core/error.h"
#include "core/resources.h"
#include "io/frame_writer.h"
#include "output/series_row.h"
#include "scene/integrator_catalogue.h"
#include "scene/scene_budget.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& flag, const std::string& message) {
  throw InputError(flag_location(flag), message);
}

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k) out += (k ? ", " : "") + words[k];
  return out;
}

// A folder the run may write into: created when missing, then proven writable by creating
// (and removing) a file in it. /dev/null, /proc, a plain file or a read-only folder fail here.
void check_writable_folder(const std::string& flag, const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    fail(flag, "'" + path + "' exists and is not a folder; " + flag + " names a folder for the outputs");
  if (!fs::exists(status)) {
    fs::create_directories(path, ec);
    if (ec) fail(flag, "cannot create the folder '" + path + "': " + ec.message());
  }
  const std::string probe = (fs::path(path) / ".periflex-write-test-XXXXXX").string();
  std::vector<char> name(probe.begin(), probe.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) fail(flag, "cannot write in the folder '" + path + "': " + std::strerror(errno));
  ::close(fd);
  ::unlink(name.data());
}

// A file the run will create or replace: not a folder, in a folder that exists and is writable.
void check_writable_file(const std::string& flag, const std::string& path) {
  if (path.empty() || path.back() == '/') fail(flag, "'" + path + "' is not a file name");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) fail(flag, "'" + path + "' is a folder; " + flag + " names a file");
  if (fs::exists(status) && !fs::is_regular_file(status))
    fail(flag, "'" + path + "' exists and is not a regular file");
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (!fs::is_directory(parent, ec)) fail(flag, "the folder of '" + path + "' does not exist");
  check_writable_folder(flag, parent.string());
}

// The movie's file: writable, and a format (by its extension) the installed ffmpeg can write,
// refused before anything is simulated instead of by ffmpeg after the run.
void check_movie_path(const std::string& path) {
  check_writable_file("--movie", path);
  check_movie_output(path, "--movie");
}

void check_number(const std::string& flag, double value, double lo, double hi, const std::string& what) {
  if (!std::isfinite(value) || value < lo || value > hi)
    fail(flag, "expected " + what + " in [" + format_number(lo) + ", " + format_number(hi) + "], found " +
                   format_number(value));
}

// --plot draws into frames, so it needs them; its names are checked once the columns are known.
void check_plot_flags(const RunOptions& o) {
  if (o.plot.empty()) {
    if (!o.plot_against.empty()) fail("--plot-against", "needs --plot Y to say what is plotted against it");
    return;
  }
  if (!o.render && !o.snapshot_at)
    fail("--plot", "draws the plot into the frames: add --render, --frames D, --movie F or --snapshot-at T");
}

// The values of `run` that need no scene.
void check_run_values(const RunOptions& o) {
  check_plot_flags(o);
  if (o.frame_every != 0.0 && (!std::isfinite(o.frame_every) || o.frame_every <= 0.0 || o.frame_every > kMaxGeometricMagnitude))
    fail("--frame-every", "expected a positive, finite number of simulated seconds, found " + format_number(o.frame_every));
  check_number("--fps", o.fps, 1.0, 240.0, "a frame rate");
  if (o.snapshot_at) check_number("--snapshot-at", *o.snapshot_at, 0.0, kMaxGeometricMagnitude, "a time");
  if (o.threads < 0) fail("--threads", "expected a thread count >= 0, found " + std::to_string(o.threads));
  if (o.vtk_every < 0) fail("--vtk-every", "expected a step count >= 0");
  if (o.checkpoint_every != 0.0 &&
      (!std::isfinite(o.checkpoint_every) || o.checkpoint_every <= 0.0 || o.checkpoint_every > kMaxGeometricMagnitude))
    fail("--checkpoint-every", "expected a positive, finite number of simulated seconds, found " +
                                   format_number(o.checkpoint_every));
  if (!o.checkpoint_dir.empty() && o.checkpoint_every == 0.0)
    fail("--checkpoint-dir", "needs --checkpoint-every T to say when checkpoints are written");
  if (!o.restart_path.empty()) {
    std::error_code ec;
    if (!fs::is_regular_file(o.restart_path, ec))
      fail("--restart", "'" + o.restart_path + "' is not a checkpoint file (" +
                            (fs::exists(o.restart_path, ec) ? "not a regular file" : "no such file") + ")");
  }
  if (!o.colormap.empty()) {
    const auto names = colormap_names();
    if (std::find(names.begin(), names.end(), o.colormap) == names.end())
      fail("--colormap", "unknown colour map '" + o.colormap + "'; expected one of: " + join(names));
  }
  if (!parse_deform_check(o.deform).empty()) fail("--deform", parse_deform_check(o.deform));
  if (!parse_camera_option(o.camera)) fail("--camera", camera_option_expected(o.camera));
  if (!o.screenshot_path.empty() && !o.snapshot_at)
    fail("--screenshot", "needs --snapshot-at T to say which simulated time the frame shows");
  if (!o.field.empty()) {
    const std::vector<std::string> fields = {"damage", "displacement", "speed", "strain"};
    if (std::find(fields.begin(), fields.end(), o.field) == fields.end())
      fail("--field", "unknown field '" + o.field + "'; expected one of: " + join(fields));
  }
}

}  // namespace

std::string safe_folder_name(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '_' || c == '.';
    out += plain ? c : '_';
  }
  // no ".", "..", or hidden folder, and a length every file system takes
  while (!out.empty() && out.front() == '.') out.erase(out.begin());
  if (out.size() > 64) out.resize(64);
  return out.empty() ? "scene" : out;
}

std::vector<std::string> colormap_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(find_resource_root()) / "assets" / "colormaps", ec))
    if (entry.path().extension() == ".png") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

double frame_interval(const RunOptions& options, const SolverDef& solver) {
  if (options.frame_every > 0) return options.frame_every;
  const double hundredth = solver.end_time / 100.0;
  // an adaptive integrator has no step to land on
  const IntegratorTraits* traits = find_integrator(solver.integrator);
  if (traits != nullptr && traits->is_adaptive) return hundredth;
  // whole steps, so that no step is cut short to land on a frame (the tolerance keeps a
  // hundredth that is a multiple of dt but for round-off from losing a step)
  const double steps = std::max(1.0, std::floor(hundredth / solver.dt * (1 + 1e-9)));
  return steps * solver.dt;
}

SceneDef load_run_scene(RunOptions& options) {
  check_run_values(options);

  // the scene, with the flags applied and the frames and threads of this run in its budget
  RunPlan plan;
  plan.threads = options.threads;
  plan.threads_where = flag_location("--threads");
  SceneDef scene = load_scene_with_options(options.scene_path, options.overrides, options.until, options.dt,
                                           options.integrator);
  if (options.render) {
    plan.frame_every = frame_interval(options, scene.solver);
    plan.frame_every_given = options.frame_every > 0;
    plan.frame_every_where =
        plan.frame_every_given ? flag_location("--frame-every") : scene.locate("limits.max_frames");
  }
  check_scene_budget(scene, plan);
  options.device_description = apply_device_option(options.device, scene);
  // the columns of this run's series.csv follow from the scene: no model is built for them
  if (!options.plot.empty()) plot_columns_checked(options, series_columns(scene));
  if (options.snapshot_at && *options.snapshot_at > scene.solver.end_time)
    fail("--snapshot-at", "t = " + format_number(*options.snapshot_at) + " s is after the end of the run (" +
                              format_number(scene.solver.end_time) + " s)");
  // VTK snapshots are files like frames
  const IntegratorTraits* integrator = find_integrator(scene.solver.integrator);
  if (options.vtk_every > 0 && (integrator == nullptr || !integrator->is_adaptive)) {
    const double files = scene.solver.end_time / scene.solver.dt / static_cast<double>(options.vtk_every);
    if (files > scene.limits.max_frames)
      fail("--vtk-every", "the run would write " + format_count(std::floor(files)) +
                              " VTK snapshots, more than limits.max_frames = " + format_count(scene.limits.max_frames));
  }

  // every output path, before anything is computed
  if (options.out_dir.empty()) options.out_dir = "out/" + safe_folder_name(scene.name);
  check_writable_folder("--out", options.out_dir);
  if (!options.frames_dir.empty()) check_writable_folder("--frames", options.frames_dir);
  if (!options.movie_path.empty()) check_movie_path(options.movie_path);
  if (!options.screenshot_path.empty()) check_writable_file("--screenshot", options.screenshot_path);
  if (options.checkpoint_every > 0.0) {
    // as many files as frames at most
    const double files = scene.solver.end_time / options.checkpoint_every;
    if (files > scene.limits.max_frames)
      fail("--checkpoint-every", "the run would write " + format_count(std::floor(files)) +
                                     " checkpoints, more than limits.max_frames = " + format_count(scene.limits.max_frames));
    if (options.checkpoint_dir.empty()) options.checkpoint_dir = options.out_dir + "/checkpoints";
    check_writable_folder("--checkpoint-dir", options.checkpoint_dir);
  }
  return scene;
}

void check_replay_flags(const RunOptions& options) {
  check_run_values(options);
  // what shapes a simulation has no meaning for states already computed
  const std::pair<bool, const char*> simulating[] = {
      {!options.overrides.empty(), "--set"},       {options.until.has_value(), "--until"},
      {options.dt.has_value(), "--dt"},            {options.integrator.has_value(), "--integrator"},
      {options.checkpoint_every != 0.0, "--checkpoint-every"}, {!options.restart_path.empty(), "--restart"},
      {options.vtk_every != 0, "--vtk-every"},     {options.frame_every != 0.0, "--frame-every"}};
  for (const auto& [given, flag] : simulating) {
    if (given) {
      fail(flag, std::string("does not apply to a checkpoint folder ('") + options.scene_path +
                     "'): it is replayed as written, one frame per state, without simulating");
    }
  }
}

void check_replay_outputs(RunOptions& options, const std::string& scene_name) {
  if (options.out_dir.empty()) options.out_dir = "out/" + safe_folder_name(scene_name) + "-replay";
  check_writable_folder("--out", options.out_dir);
  if (!options.frames_dir.empty()) check_writable_folder("--frames", options.frames_dir);
  if (!options.movie_path.empty()) check_movie_path(options.movie_path);
  if (!options.screenshot_path.empty()) check_writable_file("--screenshot", options.screenshot_path);
}

std::vector<std::string> plot_columns_checked(const RunOptions& options, const std::vector<std::string>& columns) {
  const auto check = [&](const std::string& flag, const std::string& name) {
    if (std::find(columns.begin(), columns.end(), name) == columns.end())
      fail(flag, (name.empty() ? std::string("an empty column name") : "no column '" + name + "'") +
                     " in this run's series.csv; expected one of: " + join(columns));
  };
  std::vector<std::string> names;
  size_t from = 0;
  for (;;) {
    const size_t plus = options.plot.find('+', from);
    names.push_back(options.plot.substr(from, plus == std::string::npos ? std::string::npos : plus - from));
    check("--plot", names.back());
    if (plus == std::string::npos) break;
    from = plus + 1;
  }
  if (!options.plot_against.empty()) check("--plot-against", options.plot_against);
  return names;
}

void check_gui_options(const GuiCommandOptions& options) {
  if (!options.screenshot.empty()) check_writable_file("--screenshot", options.screenshot);
  if (!parse_deform_check(options.deform).empty()) fail("--deform", parse_deform_check(options.deform));
  if (options.scene_path.empty()) return;
  SceneDef scene = load_scene_with_options(options.scene_path, options.overrides);
  // the GPU refused here (a law it does not run, no compute context), before a window opens
  apply_device_option(options.device, scene);
}

}  // namespace periflex
