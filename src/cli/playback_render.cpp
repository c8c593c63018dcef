// Frames from a checkpoint folder or a VTK series: each state put in place, snapshot, submit.
#include "cli/playback_render.h"

#include <cstdio>
#include <filesystem>

#include "cli/frame_sink.h"
#include "cli/interrupt.h"
#include "cli/run_option_checks.h"
#include "cli/scene_setup.h"
#include "core/error.h"
#include "output/atomic_file.h"
#include "output/checkpoint_file.h"
#include "io/state_replay.h"
#include "output/series_row.h"
#include "scene/toml_reader.h"

namespace periflex {

int render_checkpoint_folder(RunOptions options) {
  const std::string dir = options.scene_path;
  // a folder that cannot be replayed is bad input at the argument that names it
  auto refuse = [&](const std::string& why) { return InputError(flag_location("scene"), why); };
  check_replay_flags(options);
  std::unique_ptr<StateReplay> replay;
  try {
    replay = open_state_replay(dir);
  } catch (const CheckpointError& e) {
    throw refuse(std::string("cannot replay: ") + e.what());
  }
  check_replay_outputs(options, replay->scene().name);
  if (!options.render && !options.snapshot_at) {
    throw refuse("a checkpoint folder ('" + dir + "') is replayed into frames: add --render, --frames D or --movie F");
  }
  ensure_directory(options.out_dir);
  if (options.render && options.frames_dir.empty() && options.movie_path.empty())
    options.frames_dir = options.out_dir + "/frames";
  // the one screenshot: the state nearest the time asked for
  const size_t shot = options.snapshot_at ? replay->nearest(*options.snapshot_at) : replay->size();

  // the plot over the frames: the series rows of the states shown (a VTK series has none)
  std::vector<std::string> plot_columns;
  if (!options.plot.empty()) {
    if (!replay->has_series_rows())
      throw InputError(flag_location("--plot"), "a VTK series holds no series.csv rows to plot; replay the run's "
                                                "checkpoints, or plot while the run draws its frames");
    plot_columns = plot_columns_checked(options, series_columns(replay->simulation()));
  }

  Snapshot snapshot;
  replay->show(0, snapshot);
  std::unique_ptr<FrameSink> sink =
      make_frame_sink(options, options.out_dir, snapshot.geometry, plot_columns, replay->end_time());
  std::string error;
  int signal_number = 0;
  try {
    for (size_t k = 0; k < replay->size(); ++k) {
      if ((signal_number = pending_interrupt()) != 0) {
        error = "interrupted at the state of t = " + format_number(replay->time(k));
        break;
      }
      if (k > 0) replay->show(k, snapshot);
      if (options.render) sink->submit(snapshot);
      if (k == shot) sink->submit(snapshot, true);
    }
  } catch (const CheckpointError& e) {
    sink->finish();  // the frames in flight; the refusal is what the user needs to read
    throw refuse(std::string("cannot replay: ") + e.what());
  }
  const FrameStats stats = sink->finish();
  if (error.empty()) error = stats.error;
  if (!error.empty()) {
    std::fprintf(stderr, "periflex: error: %s\n", error.c_str());
    return signal_number != 0 ? interrupt_exit_code(signal_number) : kExitOther;
  }
  std::printf("periflex: %s replayed: %zu states from t = %.6g to %.6g s; %ld frames (render %.2f s, encode %.2f s) in %s\n",
              replay->scene().name.c_str(), replay->size(), replay->time(0), replay->time(replay->size() - 1),
              stats.frames, stats.render_seconds, stats.encode_seconds, stats.where.c_str());
  std::fflush(stdout);
  return kExitOk;
}

}  // namespace periflex
