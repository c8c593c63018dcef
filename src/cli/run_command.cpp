#include "cli/run_command.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/frame_sink.h"
#include "cli/progress_bar.h"
#include "cli/run_option_checks.h"
#include "cli/scene_setup.h"
#include "core/error.h"
#include "output/atomic_file.h"
#include "output/series_writer.h"
#include "output/summary_writer.h"
#include "output/vtk_series.h"
#include "solve/simulation.h"

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Times at which rows, frames and snapshots fall due, each an exact multiple of its interval.
struct Schedule {
  double interval = 0.0;
  long next_index = 0;
  double next_time() const { return next_index * interval; }
  bool due(double t, double eps) const { return interval > 0 && t >= next_time() - eps; }
  void advance_past(double t, double eps) {
    while (next_time() <= t + eps) ++next_index;
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

int run_command(const RunOptions& requested) {
  const auto wall_start = Clock::now();
  RunOptions options = requested;
  parse_frame_size(options);
  if (options.snapshot_at && options.screenshot_path.empty())
    throw InputError({"command line", 0, 0, "--snapshot-at"}, "needs --screenshot FILE to say where the frame goes");
  SceneDef scene = load_run_scene(options);  // every flag, the scene's budget and the output paths
  if (options.threads > 0) omp_set_num_threads(options.threads);

  const std::string out_dir = options.out_dir.empty() ? "out/" + scene.name : options.out_dir;
  ensure_directory(out_dir);
  if (options.movie_in_out_dir) options.movie_path = out_dir + "/movie.mp4";
  if (options.render && options.frames_dir.empty() && options.movie_path.empty()) options.frames_dir = out_dir + "/frames";

  Simulation sim(scene);
  const ModelInfo& info = sim.info();

  RunSummary summary;
  summary.scene = scene.name;
  summary.scene_path = scene.path;
  summary.integrator = scene.solver.integrator;
  summary.dt = scene.solver.dt;
  const std::string summary_path = out_dir + "/summary.json";
  write_summary(summary_path, info, summary);

  const bool has_particles = info.particles > 0;
  SeriesWriter series(out_dir + "/series.csv", sim.probe_columns(), has_particles);

  // Rendering and VTK output are optional; the sink checks its own preconditions first.
  std::unique_ptr<FrameSink> frames;
  Snapshot snapshot;
  if (options.render || options.snapshot_at) {
    sim.fill_snapshot(snapshot);
    frames = make_frame_sink(options, out_dir, snapshot.geometry);
  }
  std::unique_ptr<VtkSeries> vtk;
  if (options.vtk_every > 0 && has_particles) vtk = std::make_unique<VtkSeries>(out_dir + "/vtk");

  const double end_time = sim.end_time();
  const double dt = scene.solver.dt;
  const double eps = 1e-9 * dt;
  Schedule rows{scene.solver.output_interval > 0 ? scene.solver.output_interval : 10 * dt};
  Schedule frame_times;
  if (options.render) frame_times.interval = options.frame_every > 0 ? options.frame_every : end_time / 100.0;
  std::optional<double> snapshot_time = options.snapshot_at;

  ProgressBar progress(end_time, !options.quiet && stderr_is_terminal());
  double solver_seconds = 0.0;
  double last_row_time = -1.0;
  auto write_row = [&]() {
    if (!series.write(sim.sample())) {
      throw NumericalError({"output sample", sim.step_count(), sim.time(), "a value to be written is not finite",
                            "lower solver.dt or enable constraint correction"});
    }
    last_row_time = sim.time();
  };
  auto emit_due_outputs = [&]() {
    const double t = sim.time();
    if (rows.due(t, eps)) {
      write_row();
      rows.advance_past(t, eps);
    }
    const bool frame_due = frame_times.due(t, eps);
    const bool shot_due = snapshot_time && t >= *snapshot_time - eps;
    const bool vtk_due = vtk && sim.step_count() % options.vtk_every == 0;
    if (frame_due || shot_due || vtk_due) sim.fill_snapshot(snapshot);
    if (frame_due) {
      frames->submit(snapshot);
      frame_times.advance_past(t, eps);
    }
    if (shot_due) {
      frames->submit(snapshot, true);
      snapshot_time.reset();
    }
    if (vtk_due) vtk->write(snapshot);
  };

  int exit_code = kExitOk;
  try {
    sim.initialize();
    emit_due_outputs();
    while (sim.time() < end_time - eps) {
      // Land exactly on the next frame time and on the end time.
      double target = std::min(sim.time() + dt, end_time);
      if (frame_times.interval > 0) target = std::min(target, frame_times.next_time());
      if (snapshot_time) target = std::min(target, std::max(*snapshot_time, sim.time() + eps));
      const auto step_start = Clock::now();
      sim.advance_to(target);
      solver_seconds += seconds_since(step_start);
      emit_due_outputs();
      progress.update(sim.time(), sim.step_count());
    }
    // The last state is always in the series.
    if (last_row_time != sim.time()) write_row();
    summary.status = "ok";
  } catch (const NumericalError& error) {
    progress.finish();
    std::fprintf(stderr, "periflex: numerical failure: %s\n", error.what());
    summary.status = "numerical_failure";
    summary.message = error.what();
    exit_code = kExitNumerical;
  }
  progress.finish();

  FrameStats frame_stats;
  if (frames) frame_stats = frames->finish();
  if (vtk) vtk->finish();

  summary.exit_code = exit_code;
  summary.steps = sim.step_count();
  summary.simulated_time = sim.time();
  summary.solver_time = solver_seconds;
  summary.wall_time = seconds_since(wall_start);
  summary.rows_written = series.rows();
  summary.frames_written = frame_stats.frames;
  summary.render_time = frame_stats.render_seconds + frame_stats.encode_seconds;
  write_summary(summary_path, info, summary);

  std::printf("periflex: %s %s: t = %.6g s in %ld steps, %.2f s wall (solver %.2f s, %.0f steps/s)",
              scene.name.c_str(), exit_code == kExitOk ? "done" : "stopped", sim.time(), sim.step_count(),
              summary.wall_time, solver_seconds, solver_seconds > 0 ? sim.step_count() / solver_seconds : 0.0);
  if (frames && frame_stats.frames > 0) {
    // drawing and encoding ran in threads beside the solver, which only paid for the hand-over
    std::printf("; %ld frames (render %.2f s, encode %.2f s, hand-over %.2f s) in %s", frame_stats.frames,
                frame_stats.render_seconds, frame_stats.encode_seconds, frame_stats.submit_seconds,
                frame_stats.where.c_str());
  } else if (frames) {
    std::printf("; screenshot in %s", frame_stats.where.c_str());
  }
  std::printf("; outputs in %s\n", out_dir.c_str());
  return exit_code;
}

}  // namespace periflex
