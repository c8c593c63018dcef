// Off-screen recording: snapshots in, a numbered PNG sequence and/or a movie (MP4, WebM,
// Matroska, GIF or AVI: io/movie_format.h) out, plus single screenshots.
//
//   submit() --[snapshot slots]--> draw thread --[frame slots]--> file thread:  PNG sequence, screenshots
//   (copies)                       EGL context:                \-> movie thread: raw RGBA to ffmpeg
//                                  camera, draw, read back
//
// Every stage has a thread of its own, so the caller (the solver) pays for copying a snapshot only,
// and the next frame is drawn while the previous one is encoded. The slots are few and reused, so
// memory stays bounded: when a later stage falls behind, the earlier one waits for a free slot,
// and in the end so does submit(). Frames keep their submission order and numbers.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "solve/snapshot.h"

namespace periflex {

struct RecorderOptions {
  int width = 1280, height = 720;  // frame size in pixels
  int samples = 1;                 // multisamples per pixel (1: off); render/view.h default_samples()
                                   // is the usual choice; clamped to what the GL driver offers
  std::string frames_dir;          // PNG sequence DIR/frame_000000.png, ... when not empty
  std::string movie_path;          // a movie through ffmpeg when not empty, its format by its extension
  double fps = 30.0;               // the movie's playback rate
  std::string screenshot_path;     // where a frame submitted as a screenshot goes
  RenderSettings settings;         // field, colour map, what is shown
  std::string resource_root;       // shaders and colour maps; empty: find_resource_root()
  std::string ffmpeg;              // ffmpeg executable; empty: the one on PATH
  // How the view moves during the recording: kGrow fits the first frame and widens (never
  // narrows) when the scene leaves the view; kFit fits the first frame and stays; kFixed uses
  // `camera` throughout.
  enum class CameraMode { kGrow, kFit, kFixed };
  CameraMode camera_mode = CameraMode::kGrow;
  Camera camera;                   // for kFixed
  // A plot over each frame (render/plot_figure.h) of these series.csv columns, one line each,
  // against plot_against; its rows are those given to add_plot_row up to the frame's time, and
  // the frame's own (the snapshot's series row). None when empty.
  std::vector<std::string> plot_columns;
  std::string plot_against = "t";
  double plot_end_time = 0.0;      // against time: the x axis runs to it (0: to the latest row)
};

// Where the time went. Each stage runs in its own thread, so the busy times overlap and may add
// up to more than the wall time.
struct RecorderStats {
  long frames = 0;                 // sequence frames written (screenshots not counted)
  long screenshots = 0;
  int samples = 1;                 // multisamples actually used
  double draw_seconds = 0.0;       // draw thread: camera, drawing and read-back
  double png_seconds = 0.0;        // file thread: PNG encoding and writing
  double movie_seconds = 0.0;      // movie thread: handing frames to ffmpeg, which includes waiting
                                   // while ffmpeg encodes, and its closing
  double submit_seconds = 0.0;     // in submit(): copying snapshots and waiting for a free slot
  double wall_seconds = 0.0;       // from construction to the end of finish()
};

class Recorder {
 public:
  // Starts the threads: the EGL context, the frames folder and ffmpeg are set up before this
  // returns, so set-up failures are thrown here (std::runtime_error; periflex::InputError when
  // ffmpeg is missing or cannot write the movie's format).
  explicit Recorder(RecorderOptions options);
  // Finishes the frames still queued; errors are swallowed (call finish() to see them).
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Copies the snapshot as the next sequence frame, or as the screenshot (which needs
  // RecorderOptions::screenshot_path), and returns; waits while every snapshot slot is taken.
  // Rethrows the first error of any recording thread. Call from one thread at a time.
  void submit(const Snapshot& snapshot, bool screenshot = false);
  // Hands over a row for the plot (the columns of series.csv, "t" first, and their values at
  // simulation step `step`), in time order with the snapshots: each frame plots the rows up to
  // its time. Ignored without RecorderOptions::plot_columns.
  void add_plot_row(std::shared_ptr<const std::vector<std::string>> columns, std::vector<double> row, long step);
  // Waits until every submitted frame is written and the movie is closed, stops the threads and
  // returns the statistics; rethrows the first error of any recording thread. Call once.
  RecorderStats finish();
  // The statistics finish() returned, also after it threw: frames then counts the sequence
  // frames that reached every output whole (PNG files written, frames handed to ffmpeg).
  RecorderStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
