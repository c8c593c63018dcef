#include "cli/run_command.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

#include "cli/checkpoint_options.h"
#include "cli/frame_sink.h"
#include "cli/interrupt.h"
#include "cli/playback_render.h"
#include "cli/progress_bar.h"
#include "cli/run_option_checks.h"
#include "cli/scene_setup.h"
#include "core/cpu_time.h"
#include "core/thread_pool.h"
#include "core/error.h"
#include "core/sim_time.h"
#include "output/atomic_file.h"
#include "pd/bond_force_device.h"
#include "output/checkpoint_file.h"
#include "output/point_file_writer.h"
#include "output/run_record.h"
#include "output/series_row.h"
#include "io/series_writer.h"
#include "io/summary_writer.h"
#include "io/vtk_series.h"
#include "scene/toml_reader.h"
#include "solve/simulation.h"

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Times at which rows or frames fall due: k * interval exactly, each reached by a step that
// lands on it (Simulation::step_toward), whatever dt is. An interval shorter than the step would
// shorten every step, so it means "after every step" instead (at the step's own time).
struct Schedule {
  double interval = 0.0;  // 0: never
  long next_index = 0;
  bool every_step(double dt) const { return interval > 0 && interval < dt * (1 - 1e-9); }
  // the next instant the run must land on, or none (+infinity)
  double landing(double dt) const {
    return interval > 0 && !every_step(dt) ? next_time() : std::numeric_limits<double>::infinity();
  }
  double next_time() const { return static_cast<double>(next_index) * interval; }
  bool due(double t, double dt) const {
    return interval > 0 && (every_step(dt) || time_reached(t, next_time(), dt));
  }
  // the first k * interval at or after t (a run continued from a state at t)
  void start_at(double t, double dt) {
    if (interval <= 0) return;
    const double k = std::ceil((t - time_tolerance(dt, t)) / interval);
    next_index = static_cast<long>(std::clamp(k, 0.0, 9.0e18));
  }
  // the first k * interval after t (computed, not counted: no loop over skipped times)
  void advance_past(double t, double dt) {
    const double k = std::floor((t + time_tolerance(dt, t)) / interval) + 1.0;
    next_index = std::max(next_index + 1, static_cast<long>(std::min(k, 9.0e18)));
  }
};

// What the run writes besides the loop's own state, closed on every way out.
struct RunOutputs {
  std::unique_ptr<FrameSink> frames;
  std::unique_ptr<VtkSeries> vtk;
  FrameStats frame_stats;
  std::string frame_error;  // why the frames could not be finished, if they could not

  // waits for the frames in flight and closes the VTK series; a failure is kept, not thrown
  void finish() {
    if (frames) {
      frame_stats = frames->finish();
      frame_error = frame_stats.error;
      frames.reset();
    }
    if (vtk) {
      try {
        vtk->finish();
      } catch (const std::exception& e) {
        if (frame_error.empty()) frame_error = e.what();
      }
      vtk.reset();
    }
  }
};

}  // namespace

// "1280x720" -> width, height; InputError otherwise.
static void parse_frame_size(RunOptions& o) {
  if (o.size_text.empty()) return;
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(o.size_text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192)
    throw InputError({"command line", 0, 0, "--size"}, "expected WxH with 16 <= W, H <= 8192, e.g. 1280x720, not '" + o.size_text + "'");
  o.width = w;
  o.height = h;
}

int run_command(const RunOptions& options) { return run_and_report(options).exit_code; }

RunOutcome run_and_report(const RunOptions& requested) {
  RunOutcome outcome;
  std::exception_ptr& failure = outcome.failure;
  const auto wall_start = Clock::now();
  catch_interrupts();
  RunOptions options = requested;
  parse_frame_size(options);
  if (options.snapshot_at && options.screenshot_path.empty())
    throw InputError({"command line", 0, 0, "--snapshot-at"}, "needs --screenshot FILE to say where the frame goes");
  // asking for frames or a movie is asking for rendering
  if (!options.frames_dir.empty() || !options.movie_path.empty()) options.render = true;
  // a checkpoint folder instead of a scene: its states drawn, nothing simulated
  if (std::error_code ec; std::filesystem::is_directory(options.scene_path, ec)) {
    outcome.exit_code = render_checkpoint_folder(options);
    return outcome;
  }
  SceneDef scene = load_run_scene(options);  // every flag, the scene's budget and the output paths
  if (!options.points_out.empty() && scene.flex_bodies.empty())
    throw InputError({"command line", 0, 0, "--points-out"}, "scene '" + scene.name + "' has no flexible body to write");
  if (options.threads > 0) omp_set_num_threads(options.threads);

  // load_run_scene filled in the default out/<safe scene name> and checked the folder
  const std::string out_dir = options.out_dir;
  const std::string summary_path = out_dir + "/summary.json";
  ensure_directory(out_dir);
  // a summary left by an earlier run would speak for this one until it writes its own
  std::filesystem::remove(summary_path);
  if (options.movie_in_out_dir) options.movie_path = out_dir + "/movie.mp4";
  if (options.render && options.frames_dir.empty() && options.movie_path.empty()) options.frames_dir = out_dir + "/frames";

  Simulation sim(scene);
  const ModelInfo& info = sim.info();
  // the particles as the run starts from them, whatever happens to the run
  if (!options.points_out.empty()) write_point_file(options.points_out, scene);
  // the plot over the frames: columns of this run's series.csv, refused before anything is run
  std::shared_ptr<const std::vector<std::string>> plot_row_columns;
  std::vector<std::string> plot_columns;
  if (!options.plot.empty()) {
    plot_row_columns = std::make_shared<const std::vector<std::string>>(series_columns(sim));
    plot_columns = plot_columns_checked(options, *plot_row_columns);
  }

  // a restart: the checkpoint must belong to this scene and program (refused with exit 2)
  const bool checkpointing = options.checkpoint_every > 0.0;
  const uint64_t scene_hash = checkpointing || !options.restart_path.empty() ? run_scene_hash(options, scene) : 0;
  std::optional<SimState> restart;
  CheckpointHeader restart_header;
  if (!options.restart_path.empty()) restart = load_restart(options, scene, scene_hash, restart_header);
  // the folder names its scene, so it can be replayed on its own (`periflex play DIR`)
  if (checkpointing) {
    RunRecord record;
    record.scene_path = std::filesystem::absolute(options.scene_path).lexically_normal().string();
    record.overrides = options.overrides;
    record.dt = options.dt;
    record.integrator = options.integrator;
    record.until = options.until;
    record.scene_hash = scene_hash;
    record.program_version = PERIFLEX_VERSION;
    write_run_record(options.checkpoint_dir, record);
  }

  RunSummary summary;
  summary.scene = scene.name;
  summary.scene_path = scene.path;
  summary.overrides = options.overrides;
  summary.integrator = scene.solver.integrator;
  summary.device = scene.solver.device;
  summary.precision = scene.solver.device == "gpu" ? scene.solver.precision : "fp64";
  summary.device_description = options.device_description;
  summary.dt = scene.solver.dt;
  write_summary(summary_path, info, summary);

  const bool has_particles = info.particles > 0;
  std::unique_ptr<SeriesWriter> series;

  // from here on every way out rewrites summary.json with what really happened
  RunOutputs outputs;
  Snapshot snapshot;
  const double end_time = sim.end_time();
  const double dt = scene.solver.dt;
  Schedule rows{scene.solver.output_interval > 0 ? scene.solver.output_interval : 10 * dt};
  Schedule frame_times;
  if (options.render) frame_times.interval = frame_interval(options, scene.solver);
  std::optional<double> snapshot_time = options.snapshot_at;
  // checkpoints land on k * T like rows; a restart without --checkpoint-every still lands on the
  // instants of the run that wrote its file (writing none), so its steps are that run's steps
  Schedule checkpoints{checkpointing ? options.checkpoint_every : restart_header.checkpoint_every};
  long checkpoints_written = 0;

  ProgressBar progress(end_time, !options.quiet && stderr_is_terminal());
  double solver_seconds = 0.0, solver_cpu = 0.0;
  double last_row_time = -1.0;
  auto write_row = [&]() {
    if (!series->write(sim.sample())) {
      throw NumericalError({"output sample", sim.step_count(), sim.time(), "a value to be written is not finite",
                            "lower solver.dt or enable constraint correction"});
    }
    // every row in the plot over the frames, not only the frames' own
    if (!plot_columns.empty() && outputs.frames)
      outputs.frames->add_plot_row(plot_row_columns, series->last_row(), sim.step_count());
    last_row_time = sim.time();
  };
  SimState saved;  // kept between checkpoints: no allocation per file
  auto write_checkpoint_now = [&](const std::string& name) {
    CheckpointHeader header;
    header.program_version = PERIFLEX_VERSION;
    header.scene_hash = scene_hash;
    header.time = sim.time();
    header.steps = sim.step_count();
    header.checkpoint_every = options.checkpoint_every;
    sim.save_state_for_file(saved);
    const std::string path = options.checkpoint_dir + "/" + name;
    write_checkpoint(path, header, saved);
    ++checkpoints_written;
    return path;
  };
  auto emit_due_outputs = [&]() {
    const double t = sim.time();
    if (rows.due(t, dt)) {
      write_row();
      rows.advance_past(t, dt);
    }
    const bool frame_due = frame_times.due(t, dt);
    const bool shot_due = snapshot_time && time_reached(t, *snapshot_time, dt);
    const bool vtk_due = outputs.vtk && sim.step_count() % options.vtk_every == 0;
    if (frame_due || shot_due || vtk_due) {
      sim.fill_snapshot(snapshot);
      if (!plot_columns.empty()) fill_series_row(sim, plot_row_columns, snapshot);
    }
    if (frame_due) {
      outputs.frames->submit(snapshot);
      frame_times.advance_past(t, dt);
    }
    if (shot_due) {
      outputs.frames->submit(snapshot, true);
      snapshot_time.reset();
    }
    if (vtk_due) outputs.vtk->write(snapshot);
    if (checkpoints.due(t, dt)) {
      if (checkpointing) write_checkpoint_now(checkpoint_file_name(checkpoints.next_index, t));
      checkpoints.advance_past(t, dt);
    }
  };

  int exit_code = kExitOk;
  auto fail = [&](const char* status, int code, const std::string& message) {
    progress.finish();
    std::fprintf(stderr, "periflex: %s\n", message.c_str());
    summary.status = status;
    summary.message = message;
    exit_code = code;
  };
  const double worker_cpu_start = team_worker_cpu_seconds();
  try {
    // a run restarted into its own folder keeps the rows before the checkpoint: its series.csv
    // is then the whole run's
    const std::string series_path = out_dir + "/series.csv";
    const std::string earlier_rows =
        restart ? series_rows_before(series_path, series_columns(sim), restart_header.time) : std::string();
    series = std::make_unique<SeriesWriter>(series_path, sim.probe_columns(), has_particles,
                                            !sim.scene().contacts.empty(), earlier_rows);
    // rendering and VTK output are optional; the sink checks its own preconditions first
    if (options.render || options.snapshot_at) {
      sim.fill_snapshot(snapshot);
      outputs.frames = make_frame_sink(options, out_dir, snapshot.geometry, plot_columns, end_time);
    }
    if (options.vtk_every > 0) {
      outputs.vtk = std::make_unique<VtkSeries>(out_dir + "/vtk");
      snapshot.full_precision = true;  // the files keep every digit of the positions
    }

    if (restart) {
      // the state of the file, and every schedule from its time on (the row at that time again)
      try {
        sim.restore_state(*restart);
      } catch (const std::invalid_argument& e) {
        throw InputError(flag_location("--restart"), "cannot continue from '" + options.restart_path + "': " + e.what());
      }
      restart.reset();
      summary.first_step = sim.step_count();
      summary.restarted_from = options.restart_path;
      rows.start_at(sim.time(), dt);
      frame_times.start_at(sim.time(), dt);
      checkpoints.advance_past(sim.time(), dt);
    } else {
      sim.initialize();
      checkpoints.next_index = 1;  // none at t = 0
    }
    emit_due_outputs();
    while (!sim.reached(end_time)) {
      if (const int signal_number = pending_interrupt()) {
        // a checkpointing run keeps the state it reached too: a long run resumes from there
        const std::string kept =
            checkpointing ? "; the state is kept in " + write_checkpoint_now(interrupted_file_name(sim.time())) : "";
        fail("interrupted", interrupt_exit_code(signal_number),
             std::string("interrupted by ") + interrupt_name(signal_number) + " at t = " +
                 format_number(sim.time()) + " s" + kept);
        break;
      }
      // the next instant something is due: the end, a row, a frame or the screenshot
      double target = std::min({end_time, rows.landing(dt), frame_times.landing(dt), checkpoints.landing(dt)});
      if (snapshot_time) target = std::min(target, *snapshot_time);
      const auto step_start = Clock::now();
      const double cpu_start = thread_cpu_seconds();
      sim.step_toward(target);
      solver_cpu += thread_cpu_seconds() - cpu_start;
      solver_seconds += seconds_since(step_start);
      emit_due_outputs();
      progress.update(sim.time(), sim.step_count());
    }
    // the last state is always in the series, and in the VTK snapshots when N steps do not
    // divide the run's
    if (last_row_time != sim.time()) write_row();
    if (outputs.vtk && sim.step_count() % options.vtk_every != 0) {
      sim.fill_snapshot(snapshot);
      outputs.vtk->write(snapshot);
    }
    if (exit_code == kExitOk) summary.status = "ok";
  } catch (const NumericalError& error) {
    failure = std::current_exception();
    fail("numerical_failure", kExitNumerical, std::string("numerical failure: ") + error.what());
  } catch (const InputError& error) {
    failure = std::current_exception();
    fail("bad_input", kExitBadInput, std::string("error: ") + error.what());
  } catch (const DeviceError& error) {
    failure = std::current_exception();
    fail("device_failure", kExitNumerical, std::string("GPU failure: ") + error.what());
  } catch (const std::exception& error) {
    failure = std::current_exception();
    fail("error", kExitOther, std::string("error: ") + error.what());
  }
  progress.finish();
  solver_cpu += team_worker_cpu_seconds() - worker_cpu_start;

  outputs.finish();
  if (!outputs.frame_error.empty() && exit_code == kExitOk) {
    fail("error", kExitOther, "error: " + outputs.frame_error);
    failure = std::make_exception_ptr(std::runtime_error(outputs.frame_error));
  }
  const FrameStats& frame_stats = outputs.frame_stats;

  summary.exit_code = exit_code;
  summary.steps = sim.step_count();
  summary.simulated_time = sim.time();
  summary.solver_time = solver_seconds;
  summary.solver_cpu_time = solver_cpu;
  summary.wall_time = seconds_since(wall_start);
  summary.rows_written = series ? series->rows() : 0;
  summary.frames_written = frame_stats.frames;
  summary.render_time = frame_stats.render_seconds + frame_stats.encode_seconds;
  write_summary(summary_path, info, summary);

  const char* verb = exit_code == kExitOk ? "done" : summary.status == "interrupted" ? "interrupted" : "stopped";
  std::printf("periflex: %s %s: t = %.6g s in %ld steps, %.2f s wall (solver %.2f s wall, %.2f s CPU, %.0f steps/s)",
              scene.name.c_str(), verb, sim.time(), sim.step_count(), summary.wall_time, solver_seconds, solver_cpu,
              steps_per_second(summary));
  if (frame_stats.frames > 0) {
    // drawing and encoding ran in threads beside the solver, which only paid for the hand-over
    std::printf("; %ld frames (render %.2f s, encode %.2f s, hand-over %.2f s) in %s", frame_stats.frames,
                frame_stats.render_seconds, frame_stats.encode_seconds, frame_stats.submit_seconds,
                frame_stats.where.c_str());
  }
  if (frame_stats.screenshot_written) std::printf("; screenshot in %s", options.screenshot_path.c_str());
  if (checkpoints_written > 0) std::printf("; %ld checkpoints in %s", checkpoints_written, options.checkpoint_dir.c_str());
  std::printf("; outputs in %s\n", out_dir.c_str());
  std::fflush(stdout);
  outcome.exit_code = exit_code;
  outcome.out_dir = out_dir;
  return outcome;
}

}  // namespace periflex
