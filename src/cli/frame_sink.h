// Where rendered frames go during a headless run: the off-screen recorder when the program
// is built with EGL, otherwise nothing (asking for frames then is bad input).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "solve/snapshot.h"

namespace periflex {

// Where the recording's time went. Drawing and encoding run in threads of their own, at the
// same time, so the two may add up to more than the run's wall time.
struct FrameStats {
  long frames = 0;
  double render_seconds = 0.0;  // drawing and read-back, in the draw thread
  double encode_seconds = 0.0;  // PNG encoding and writing plus feeding ffmpeg, in the encoder threads
  double submit_seconds = 0.0;  // what the solver's thread spent handing snapshots over
  bool screenshot_written = false;
  std::string where;            // frames directory / movie / screenshot written
  std::string error;            // why the frames could not all be written (frames: those that were)
};

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // Hands a snapshot over as the next movie / sequence frame, or as the single screenshot;
  // returns once it is copied (the drawing and encoding happen in other threads). Throws
  // std::runtime_error when an earlier frame failed.
  virtual void submit(const Snapshot& snapshot, bool screenshot = false) = 0;
  // A row of series.csv for the plot over the frames (make_frame_sink's plot_columns), in time
  // order with the snapshots.
  virtual void add_plot_row(std::shared_ptr<const std::vector<std::string>> columns, std::vector<double> row,
                            long step) = 0;
  // Waits for every frame to be written. A failure is told in FrameStats::error, not thrown.
  virtual FrameStats finish() = 0;
};

// Checks what can be checked before simulating (ffmpeg present, output writable, sizes valid);
// throws InputError. Then creates the sink: multisampling as options.samples says, or when that is
// 0 as default_samples() of the geometry's particle count. With plot_columns (checked), each frame
// carries a plot of them, its time axis to end_time; the snapshots must carry their series rows.
std::unique_ptr<FrameSink> make_frame_sink(const RunOptions& options, const std::string& out_dir,
                                           std::shared_ptr<const SceneGeometry> geometry,
                                           const std::vector<std::string>& plot_columns = {},
                                           double end_time = 0.0);

}  // namespace periflex
