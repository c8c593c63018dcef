#include "cli/frame_sink.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "core/error.h"

#ifdef PERIFLEX_WITH_HEADLESS
#include "headless/offscreen_renderer.h"
#include "render/frame_writer.h"
#include "render/view.h"
#endif

namespace periflex {

#ifndef PERIFLEX_WITH_HEADLESS

std::unique_ptr<FrameSink> make_frame_sink(const RunOptions&, const std::string&,
                                           std::shared_ptr<const SceneGeometry>) {
  throw InputError({"command line", 0, 0, "--render"},
                   "this build has no off-screen renderer (configured with -DPERIFLEX_HEADLESS=OFF)");
}

#else

namespace {

using Clock = std::chrono::steady_clock;

ColorField parse_field(const std::string& name) {
  if (name.empty() || name == "damage") return ColorField::kDamage;
  if (name == "displacement") return ColorField::kDisplacement;
  if (name == "speed") return ColorField::kSpeed;
  if (name == "strain") return ColorField::kStrain;
  throw InputError({"command line", 0, 0, "--field"},
                   "unknown field '" + name + "'; expected damage, displacement, speed or strain");
}

// Draws snapshots in a thread of its own (which owns the EGL context), so the solver only pays
// for a copy. The queue is bounded: when encoding falls behind, submit waits, which bounds memory.
class OffscreenFrameSink : public FrameSink {
 public:
  OffscreenFrameSink(const RunOptions& options, RenderSettings settings)
      : options_(options), settings_(std::move(settings)) {
    worker_ = std::thread([this] { work(); });
    // Surface set-up failures (no EGL, missing shaders) before the run starts.
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return ready_ || error_; });
    if (error_) {
      lock.unlock();
      worker_.join();
      std::rethrow_exception(error_);
    }
  }

  ~OffscreenFrameSink() override {
    if (worker_.joinable()) {
      try {
        finish();
      } catch (...) {
      }
    }
  }

  void submit(const Snapshot& snapshot, bool screenshot) override {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < kMaxQueued || error_; });
    if (error_) std::rethrow_exception(error_);
    queue_.push_back({snapshot, screenshot});
    changed_.notify_all();
  }

  FrameStats finish() override {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
      changed_.notify_all();
    }
    if (worker_.joinable()) worker_.join();
    if (error_) std::rethrow_exception(error_);
    return stats_;
  }

 private:
  static constexpr size_t kMaxQueued = 4;
  struct Item {
    Snapshot snapshot;
    bool screenshot;
  };

  void work() {
    try {
      OffscreenRenderer renderer(options_.width, options_.height);
      std::unique_ptr<PngSequenceWriter> pngs;
      std::unique_ptr<Mp4Writer> movie;
      if (!options_.frames_dir.empty()) pngs = std::make_unique<PngSequenceWriter>(options_.frames_dir);
      if (!options_.movie_path.empty())
        movie = std::make_unique<Mp4Writer>(options_.movie_path, options_.width, options_.height, options_.fps);
      {
        std::lock_guard lock(mutex_);
        ready_ = true;
        changed_.notify_all();
      }

      Camera camera;
      bool have_camera = false;
      RgbaImage image;
      for (;;) {
        Item item;
        {
          std::unique_lock lock(mutex_);
          changed_.wait(lock, [this] { return !queue_.empty() || closing_; });
          if (queue_.empty()) break;
          item = std::move(queue_.front());
          queue_.pop_front();
          changed_.notify_all();
        }
        // Fit once; widen the view (never narrow it) when particles fly out of it.
        const Camera fitted = fit_camera(item.snapshot, options_.width, options_.height);
        if (!have_camera) camera = fitted, have_camera = true;
        const Bounds now = snapshot_bounds(item.snapshot);
        const double aspect = double(options_.width) / options_.height;
        const Vec2 half(0.5 * camera.view_height * aspect, 0.5 * camera.view_height);
        Bounds view;
        view.add(camera.center - half);
        view.add(camera.center + half);
        if (!now.empty() && !view.contains(now)) camera.fit(now.lo, now.hi, aspect);

        const auto draw_start = Clock::now();
        renderer.render(item.snapshot, camera, settings_, image);
        const auto encode_start = Clock::now();
        if (item.screenshot) {
          write_png(options_.screenshot_path, image);
        } else {
          if (pngs) pngs->write(image);
          if (movie) movie->write(image);
          ++stats_.frames;
        }
        stats_.render_seconds += std::chrono::duration<double>(encode_start - draw_start).count();
        stats_.encode_seconds += std::chrono::duration<double>(Clock::now() - encode_start).count();
      }
      if (movie) movie->close();
      stats_.where = options_.movie_path.empty() ? options_.frames_dir
                     : options_.frames_dir.empty() ? options_.movie_path
                                                   : options_.frames_dir + " and " + options_.movie_path;
      if (!options_.screenshot_path.empty())
        stats_.where += (stats_.where.empty() ? "" : " and ") + options_.screenshot_path;
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
    }
  }

  RunOptions options_;
  RenderSettings settings_;
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Item> queue_;
  bool ready_ = false, closing_ = false;
  std::exception_ptr error_;
  FrameStats stats_;
};

}  // namespace

std::unique_ptr<FrameSink> make_frame_sink(const RunOptions& options, const std::string& out_dir,
                                           std::shared_ptr<const SceneGeometry> geometry) {
  RenderSettings settings;
  settings.field = parse_field(options.field);
  if (!options.colormap.empty()) settings.colormap = options.colormap;
  if (!options.movie_path.empty()) check_movie_output(options.movie_path, "--movie");
  return std::make_unique<OffscreenFrameSink>(options, settings);
}

#endif

}  // namespace periflex
