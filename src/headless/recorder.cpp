#include "headless/recorder.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "headless/offscreen_renderer.h"
#include "io/frame_writer.h"
#include "io/image.h"
#include "render/plot_figure.h"
#include "render/view.h"

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Snapshots waiting to be drawn (plus the one being drawn), and frames being encoded. Two
// snapshots let the solver run a frame ahead of the drawing; four frames let the drawing run
// ahead of a slower encoder (ffmpeg) without holding more than a few frames of memory.
constexpr int kSnapshotSlots = 2;
constexpr int kFrameSlots = 4;

}  // namespace

struct Recorder::Impl {
  struct Job {
    Snapshot snapshot;
    bool screenshot = false;
  };
  struct Frame {
    RgbaImage image;
    bool screenshot = false;
    long index = 0;    // number in the sequence
    int pending = 0;   // encoder threads that still need it
  };

  RecorderOptions options;
  std::unique_ptr<PngSequenceWriter> pngs;
  std::unique_ptr<MovieWriter> movie;
  std::thread draw_thread, file_thread, movie_thread;
  Clock::time_point start = Clock::now();

  // Everything below is shared between the threads and guarded by the mutex; the slots' contents
  // are not: a slot belongs to whichever stage took it off a list until it is put on another.
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<Job> jobs = std::vector<Job>(kSnapshotSlots);
  std::vector<Frame> frames = std::vector<Frame>(kFrameSlots);
  std::deque<int> free_jobs, jobs_to_draw;
  std::deque<int> free_frames, frames_to_file, frames_to_movie;
  // rows for the plot, in time order, not yet drawn
  struct PlotRow {
    std::shared_ptr<const std::vector<std::string>> columns;
    std::vector<double> values;
    long step = 0;
  };
  std::deque<PlotRow> plot_rows_waiting;
  bool renderer_ready = false;
  bool closing = false;       // no more submissions
  bool drawing_done = false;  // the draw thread has handed over its last frame
  bool finished = false;
  std::exception_ptr error;   // the first failure of any thread

  // Written by one thread each (submit_seconds by the caller's), read after they are joined.
  double draw_seconds = 0.0, png_seconds = 0.0, movie_seconds = 0.0, submit_seconds = 0.0;
  long sequence_frames = 0, screenshots = 0;
  long files_written = 0;  // sequence frames written to PNG files
  int samples_used = 1;
  RecorderStats stats;  // what finish() found

  void fail(std::exception_ptr e) {
    std::lock_guard lock(mutex);
    if (!error) error = e;
    changed.notify_all();
  }
  void release_frame(int f) {
    std::lock_guard lock(mutex);
    if (--frames[f].pending == 0) {
      free_frames.push_back(f);
      changed.notify_all();
    }
  }
  void draw_loop();
  void file_loop();
  void movie_loop();
  void stop_threads();
};

// ---------------------------------------------------------------------------
// Draw thread: owns the EGL context.

void Recorder::Impl::draw_loop() {
  try {
    OffscreenRenderer renderer(options.width, options.height, options.samples,
                               options.resource_root.empty() ? find_resource_root() : options.resource_root);
    {
      std::lock_guard lock(mutex);
      samples_used = renderer.samples();
      renderer_ready = true;
      changed.notify_all();
    }
    Camera camera;
    bool have_camera = false;
    // the plot over the frames: every frame's series row, the x axis over them
    PlotHistory plot_rows(20000);
    OverlayPlot plot;
    plot.history = &plot_rows;
    plot.view.x_column = options.plot_against;
    plot.view.y_columns = options.plot_columns;
    for (;;) {
      // the next snapshot, in submission order
      int j = 0;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [this] { return !jobs_to_draw.empty() || closing || error; });
        if (error || jobs_to_draw.empty()) break;
        j = jobs_to_draw.front();
        jobs_to_draw.pop_front();
      }
      const Job& job = jobs[j];

      // the view: set by the user, or fitted once; when growing, widened (never narrowed) when
      // what is drawn leaves it
      const auto draw_start = Clock::now();
      using Mode = RecorderOptions::CameraMode;
      if (!have_camera) {
        camera = options.camera_mode == Mode::kFixed ? options.camera
                                                     : fit_camera(job.snapshot, options.width, options.height);
        have_camera = true;
      }
      if (options.camera_mode == Mode::kGrow) widen_to_show(camera, job.snapshot, options.width, options.height);

      // a free frame to draw into
      int f = 0;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [this] { return !free_frames.empty() || error; });
        if (error) break;
        f = free_frames.front();
        free_frames.pop_front();
      }
      Frame& frame = frames[f];
      const bool plotted = !options.plot_columns.empty();
      if (plotted) {
        // the rows up to the frame's time, then the frame's own
        std::vector<PlotRow> due;
        {
          std::lock_guard lock(mutex);
          while (!plot_rows_waiting.empty() && plot_rows_waiting.front().step <= job.snapshot.step) {
            due.push_back(std::move(plot_rows_waiting.front()));
            plot_rows_waiting.pop_front();
          }
        }
        for (const PlotRow& r : due) plot_rows.add_row(*r.columns, r.values, r.step, 0.0);
        plot_rows.add(job.snapshot, 0.0);
        if (plot_column_range(plot_rows, plot.view.x_column, plot.view.x_lo, plot.view.x_hi) &&
            plot.view.x_column == "t" && options.plot_end_time > 0.0) {
          plot.view.x_lo = std::min(0.0, plot_rows.first_time());
          plot.view.x_hi = std::max(options.plot_end_time, plot_rows.last_time());
        }
        plot.view.cursor_time = job.snapshot.time;
      }
      renderer.render(job.snapshot, camera, options.settings, frame.image, plotted ? &plot : nullptr);
      frame.screenshot = job.screenshot;
      frame.index = job.screenshot ? -1 : sequence_frames;
      if (job.screenshot)
        ++screenshots;
      else
        ++sequence_frames;
      draw_seconds += seconds_between(draw_start, Clock::now());

      // the snapshot slot back to submit(), the frame on to the encoders that want it
      std::lock_guard lock(mutex);
      free_jobs.push_back(j);
      frame.pending = 0;
      if (frame.screenshot || pngs) frames_to_file.push_back(f), ++frame.pending;
      if (!frame.screenshot && movie) frames_to_movie.push_back(f), ++frame.pending;
      if (frame.pending == 0) free_frames.push_back(f);
      changed.notify_all();
    }
  } catch (...) {
    fail(std::current_exception());
  }
  std::lock_guard lock(mutex);
  drawing_done = true;
  changed.notify_all();
}

// ---------------------------------------------------------------------------
// Encoder threads: PNG files, and the movie.

void Recorder::Impl::file_loop() {
  try {
    for (;;) {
      int f = 0;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [this] { return !frames_to_file.empty() || drawing_done || error; });
        if (error || frames_to_file.empty()) return;
        f = frames_to_file.front();
        frames_to_file.pop_front();
      }
      const auto start_write = Clock::now();
      const Frame& frame = frames[f];
      if (frame.screenshot) {
        write_png(options.screenshot_path, frame.image);
      } else {
        pngs->write_numbered(frame.index, frame.image);
        ++files_written;
      }
      png_seconds += seconds_between(start_write, Clock::now());
      release_frame(f);
    }
  } catch (...) {
    fail(std::current_exception());
  }
}

void Recorder::Impl::movie_loop() {
  try {
    for (;;) {
      int f = 0;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [this] { return !frames_to_movie.empty() || drawing_done || error; });
        if (error) return;
        if (frames_to_movie.empty()) break;
        f = frames_to_movie.front();
        frames_to_movie.pop_front();
      }
      const auto start_write = Clock::now();
      movie->write(frames[f].image);
      movie_seconds += seconds_between(start_write, Clock::now());
      release_frame(f);
    }
    // every frame handed over: ffmpeg finishes the file
    const auto start_close = Clock::now();
    movie->close();
    movie_seconds += seconds_between(start_close, Clock::now());
  } catch (...) {
    fail(std::current_exception());
  }
}

void Recorder::Impl::stop_threads() {
  {
    std::lock_guard lock(mutex);
    closing = true;
    changed.notify_all();
  }
  for (std::thread* t : {&draw_thread, &file_thread, &movie_thread})
    if (t->joinable()) t->join();
}

// ---------------------------------------------------------------------------

Recorder::Recorder(RecorderOptions options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = std::move(options);
  for (int j = 0; j < kSnapshotSlots; ++j) m.free_jobs.push_back(j);
  for (int f = 0; f < kFrameSlots; ++f) m.free_frames.push_back(f);

  // the EGL context first: without it nothing else is worth starting
  m.draw_thread = std::thread([&m] { m.draw_loop(); });
  {
    std::unique_lock lock(m.mutex);
    m.changed.wait(lock, [&m] { return m.renderer_ready || m.error; });
  }
  try {
    if (m.error) std::rethrow_exception(m.error);
    if (!m.options.frames_dir.empty()) m.pngs = std::make_unique<PngSequenceWriter>(m.options.frames_dir);
    if (!m.options.movie_path.empty())
      m.movie = std::make_unique<MovieWriter>(m.options.movie_path, m.options.width, m.options.height, m.options.fps,
                                            m.options.ffmpeg);
  } catch (...) {
    m.stop_threads();
    throw;
  }
  // the writers are set before any frame can reach the encoders (submit takes the mutex)
  m.file_thread = std::thread([&m] { m.file_loop(); });
  if (m.movie) m.movie_thread = std::thread([&m] { m.movie_loop(); });
}

Recorder::~Recorder() {
  if (!impl_->finished) {
    try {
      finish();
    } catch (...) {
      // a destructor cannot report; finish() does
    }
  }
}

void Recorder::submit(const Snapshot& snapshot, bool screenshot) {
  Impl& m = *impl_;
  const auto start = Clock::now();
  if (screenshot && m.options.screenshot_path.empty())
    throw std::invalid_argument("a screenshot was submitted, but the recorder has no screenshot path");
  int j = 0;
  {
    std::unique_lock lock(m.mutex);
    if (m.closing) throw std::logic_error("Recorder::submit after finish");
    m.changed.wait(lock, [&m] { return !m.free_jobs.empty() || m.error; });
    if (m.error) std::rethrow_exception(m.error);
    j = m.free_jobs.front();
    m.free_jobs.pop_front();
  }
  // the copy outside the lock, into a slot only this thread holds (its vectors are reused)
  m.jobs[j].snapshot = snapshot;
  m.jobs[j].screenshot = screenshot;
  {
    std::lock_guard lock(m.mutex);
    m.jobs_to_draw.push_back(j);
    m.changed.notify_all();
  }
  m.submit_seconds += seconds_between(start, Clock::now());
}

void Recorder::add_plot_row(std::shared_ptr<const std::vector<std::string>> columns, std::vector<double> row,
                            long step) {
  Impl& m = *impl_;
  if (m.options.plot_columns.empty()) return;
  std::lock_guard lock(m.mutex);
  m.plot_rows_waiting.push_back({std::move(columns), std::move(row), step});
}

RecorderStats Recorder::finish() {
  Impl& m = *impl_;
  if (m.finished) throw std::logic_error("Recorder::finish called twice");
  m.stop_threads();
  m.finished = true;
  // after a failure elsewhere the movie is still open: end ffmpeg now, not at destruction
  if (m.movie) {
    try {
      m.movie->close();
    } catch (...) {
      if (!m.error) m.error = std::current_exception();
    }
  }
  RecorderStats& stats = m.stats;
  stats.frames = m.sequence_frames;
  // after a failure, the frames drawn are not all written: count those every output has
  if (m.error) {
    if (m.pngs) stats.frames = std::min(stats.frames, m.files_written);
    if (m.movie) stats.frames = std::min(stats.frames, m.movie->frames_written());
  }
  m.movie.reset();
  stats.screenshots = m.screenshots;
  stats.samples = m.samples_used;
  stats.draw_seconds = m.draw_seconds;
  stats.png_seconds = m.png_seconds;
  stats.movie_seconds = m.movie_seconds;
  stats.submit_seconds = m.submit_seconds;
  stats.wall_seconds = seconds_between(m.start, Clock::now());
  if (m.error) std::rethrow_exception(m.error);
  return stats;
}

RecorderStats Recorder::stats() const { return impl_->stats; }

}  // namespace periflex
