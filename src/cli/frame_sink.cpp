#include "cli/frame_sink.h"

#include <cmath>
#include <cstdio>

#include "cli/camera_option.h"
#include "cli/gui_command.h"
#include "core/error.h"

#ifdef PERIFLEX_WITH_HEADLESS
#include "headless/recorder.h"
#include "io/frame_writer.h"
#include "render/view.h"
#endif

namespace periflex {

#ifndef PERIFLEX_WITH_HEADLESS

std::unique_ptr<FrameSink> make_frame_sink(const RunOptions&, const std::string&,
                                           std::shared_ptr<const SceneGeometry>, const std::vector<std::string>&,
                                           double) {
  throw InputError({"command line", 0, 0, "--render"},
                   "this build has no off-screen renderer (configured with -DPERIFLEX_HEADLESS=OFF)");
}

#else

namespace {

ColorField parse_field(const std::string& name) {
  if (name.empty() || name == "damage") return ColorField::kDamage;
  if (name == "displacement") return ColorField::kDisplacement;
  if (name == "speed") return ColorField::kSpeed;
  if (name == "strain") return ColorField::kStrain;
  throw InputError({"command line", 0, 0, "--field"},
                   "unknown field '" + name + "'; expected damage, displacement, speed or strain");
}

// --camera, checked with the other flags before the scene was built.
void set_camera(const std::string& text, RecorderOptions& recorder) {
  using Mode = RecorderOptions::CameraMode;
  const std::optional<CameraOption> camera = parse_camera_option(text);
  if (!camera) throw InputError({"command line", 0, 0, "--camera"}, camera_option_expected(text));
  recorder.camera_mode = camera->mode == CameraOption::Mode::kGrow  ? Mode::kGrow
                         : camera->mode == CameraOption::Mode::kFit ? Mode::kFit
                                                                    : Mode::kFixed;
  recorder.camera.center = Vec2(camera->center_x, camera->center_y);
  recorder.camera.view_height = camera->view_height;
}

// The run's frames go through the off-screen recording pipeline (headless/recorder.h).
class RecorderFrameSink : public FrameSink {
 public:
  RecorderFrameSink(RecorderOptions options, std::string where)
      : recorder_(std::move(options)), where_(std::move(where)) {}

  void submit(const Snapshot& snapshot, bool screenshot) override { recorder_.submit(snapshot, screenshot); }
  void add_plot_row(std::shared_ptr<const std::vector<std::string>> columns, std::vector<double> row,
                    long step) override {
    recorder_.add_plot_row(std::move(columns), std::move(row), step);
  }

  FrameStats finish() override {
    FrameStats stats;
    try {
      recorder_.finish();
    } catch (const std::exception& e) {
      stats.error = e.what();
    }
    const RecorderStats recorded = recorder_.stats();
    stats.frames = recorded.frames;
    stats.render_seconds = recorded.draw_seconds;
    stats.encode_seconds = recorded.png_seconds + recorded.movie_seconds;
    stats.submit_seconds = recorded.submit_seconds;
    stats.screenshot_written = recorded.screenshots > 0;
    stats.where = where_;
    return stats;
  }

 private:
  Recorder recorder_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FrameSink> make_frame_sink(const RunOptions& options, const std::string& out_dir,
                                           std::shared_ptr<const SceneGeometry> geometry,
                                           const std::vector<std::string>& plot_columns, double end_time) {
  RecorderOptions recorder;
  recorder.width = options.width;
  recorder.height = options.height;
  const long particles = geometry ? static_cast<long>(geometry->reference_x.size()) : 0;
  recorder.samples = options.samples > 0 ? options.samples : default_samples(particles);
  recorder.frames_dir = options.frames_dir;
  recorder.movie_path = options.movie_path;
  recorder.fps = options.fps;
  recorder.screenshot_path = options.screenshot_path;
  recorder.settings.field = parse_field(options.field);
  set_camera(options.camera, recorder);
  if (!options.colormap.empty()) recorder.settings.colormap = options.colormap;
  recorder.settings.show_contacts = options.draw_contacts;
  double deform = -1.0;
  if (!parse_deform(options.deform, deform))
    throw InputError({"command line", 0, 0, "--deform"}, parse_deform_check(options.deform));
  recorder.settings.deform = static_cast<float>(deform);
  recorder.plot_columns = plot_columns;
  if (!options.plot_against.empty()) recorder.plot_against = options.plot_against;
  recorder.plot_end_time = end_time;
  if (!options.movie_path.empty()) check_movie_output(options.movie_path, "--movie");

  // what the closing line names
  std::string where = options.movie_path.empty() ? options.frames_dir
                      : options.frames_dir.empty() ? options.movie_path
                                                   : options.frames_dir + " and " + options.movie_path;
  if (!options.screenshot_path.empty()) where += (where.empty() ? "" : " and ") + options.screenshot_path;
  return std::make_unique<RecorderFrameSink>(std::move(recorder), std::move(where));
}

#endif

}  // namespace periflex
