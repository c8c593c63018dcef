// Recording from the window: the simulation thread publishes snapshots at a fixed simulated-time
// interval; the main thread draws each, with the overlay a screenshot shows (scene name, time,
// colour legend) but without the panels, into an off-screen framebuffer of the window's size and
// hands the pixels to a frame writer (PNG sequence, or a movie through ffmpeg in the format its
// extension names: io/movie_format.h) that writes on its own thread (io/background_frame_writer.h).
#include <algorithm>
#include <exception>
#include <stdexcept>

#include "app/gui_app.h"
#include "app/view_fit.h"
#include "render/gl.h"
#include "io/image.h"
#include "io/movie_format.h"

namespace periflex {

namespace {

// recorded frames drawn per window frame, so recording never stalls the interface for long
constexpr int kRecordedPerFrame = 4;
// frames drawn and waiting for the encoder's thread (4 MB each at 1280x800): when they are all
// taken, the simulation waits for the encoder, the window does not
constexpr size_t kFramesToEncoder = 2;

}  // namespace

void GuiApp::start_recording(const std::string& path, double interval, double fps, int fb_width,
                             int fb_height) {
  if (writer_) stop_recording();
  if (path.empty() || interval <= 0.0) {
    record_message_ = "give a folder or a movie file (.mp4, .webm, .mkv, .gif, .avi) and a positive interval";
    return;
  }
  // even sizes: movies need them
  record_width_ = std::max(2, fb_width & ~1);
  record_height_ = std::max(2, fb_height & ~1);
  try {
    // a movie extension makes a movie (its format checked against this ffmpeg); anything else
    // names the folder of a PNG sequence
    if (movie_format_of(path)) {
      if (find_ffmpeg().empty()) {
        record_message_ = "ffmpeg is not installed (not on PATH): install it, or record a PNG sequence "
                          "by giving a folder name";
        log_.add("recording: " + record_message_);
        return;
      }
      writer_ = std::make_unique<BackgroundFrameWriter>(
          std::make_unique<MovieWriter>(path, record_width_, record_height_, std::max(1.0, fps)), kFramesToEncoder);
    } else {
      writer_ = std::make_unique<BackgroundFrameWriter>(std::make_unique<PngSequenceWriter>(path), kFramesToEncoder);
    }
  } catch (const std::exception& e) {
    record_message_ = e.what();
    log_.add("recording could not start: " + record_message_);
    writer_.reset();
    return;
  }

  // the off-screen target the recorded frames are drawn into
  if (!make_target(record_width_, record_height_, fbo_, color_rbo_)) {
    record_message_ = "the off-screen framebuffer for recording is incomplete";
    log_.add("recording could not start: " + record_message_);
    writer_.reset();
    return;
  }
  // the movie keeps the camera the window has now (the window stops growing its view too)
  record_camera_ = picture_camera(camera_, record_height_);
  record_rows_.clear();
  record_message_ = "recording to " + path;
  send(SimCommand{command::Record{interval}});
}

RgbaImage GuiApp::draw_picture(const Snapshot& frame, const Camera& camera, unsigned fbo, int width, int height,
                               const PlotHistory& rows) {
  // the plot window's plot: its series against its x column, over the range it shows when
  // zoomed, else over every row; the cursor at the picture's time
  OverlayPlot plot;
  const bool plotted = show_plot_ && rows.size() > 0;
  if (plotted) {
    plot.history = &rows;
    plot.view = plot_view(frame.time);
    plot.view.x_lo = plot_x_lo_;
    plot.view.x_hi = plot_x_hi_;
    if (!plot_zoomed_) plot_column_range(rows, plot_x_, plot.view.x_lo, plot.view.x_hi);
  }
  // draw off-screen with the overlay, read back (rows bottom-up in GL)
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  renderer_->draw(frame, camera, render_, width, height);
  if (frame.geometry) renderer_->draw_overlay(frame, render_, width, height, 0, plotted ? &plot : nullptr);
  RgbaImage image;
  image.resize(width, height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  flip_rows(image);
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  return image;
}

bool GuiApp::make_target(int width, int height, unsigned& fbo, unsigned& rbo) {
  glGenFramebuffers(1, &fbo);
  glGenRenderbuffers(1, &rbo);
  glBindRenderbuffer(GL_RENDERBUFFER, rbo);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rbo);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rbo);
    fbo = rbo = 0;
  }
  return complete;
}

void GuiApp::write_picture(const std::string& path, int fb_width, int fb_height) {
  // a screenshot is framed as a recorded frame: the window's picture without the panels, drawn
  // off-screen, so the window itself keeps its panels (no blank strip, no flicker)
  const Snapshot& snap = worker_.snapshot();
  unsigned fbo = 0, rbo = 0;
  try {
    if (!snap.geometry) throw std::runtime_error("nothing drawn yet");
    if (!make_target(fb_width, fb_height, fbo, rbo)) throw std::runtime_error("off-screen framebuffer incomplete");
    const RgbaImage image = draw_picture(snap, picture_camera(camera_, fb_height), fbo, fb_width, fb_height, history_);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rbo);
    write_png(path, image);
    log_.add("screenshot " + path + " (" + std::to_string(fb_width) + "x" + std::to_string(fb_height) +
             ", t = " + std::to_string(snap.time) + ")");
  } catch (const std::exception& e) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (rbo) glDeleteRenderbuffers(1, &rbo);
    log_.add(std::string("screenshot failed: ") + e.what());
    if (options_.frames > 0) exit_code_ = kExitOther;
  }
}

void GuiApp::write_recorded_frame(const Snapshot& frame, FrameWriter& writer) {
  // the camera the recording started with: a movie's view does not jump
  // the plot over a movie grows with it: the rows of the frames recorded so far
  record_rows_.add(frame, 0.0);
  writer.write(draw_picture(frame, record_camera_, fbo_, record_width_, record_height_, record_rows_));
}

void GuiApp::pump_recording() {
  if (!writer_) return;
  Snapshot frame;
  for (int n = 0; n < kRecordedPerFrame && writer_->ready() && worker_.take_recorded(frame); ++n) {
    try {
      write_recorded_frame(frame, *writer_);
    } catch (const std::exception& e) {
      // a full disk or a dead ffmpeg ends the recording with the reason shown
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      record_message_ = std::string("recording stopped: ") + e.what();
      log_.add(record_message_);
      stop_recording();
      return;
    }
  }
}

void GuiApp::stop_recording() {
  if (!writer_) return;
  send(SimCommand{command::Record{0.0}});
  // frames already published are still written
  std::unique_ptr<BackgroundFrameWriter> writer = std::move(writer_);
  Snapshot frame;
  try {
    while (worker_.take_recorded(frame)) write_recorded_frame(frame, *writer);
    writer->close();
    record_message_ = "recorded " + std::to_string(writer->frames_written()) + " frames";
  } catch (const std::exception& e) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    record_message_ = std::string("recording ended with an error: ") + e.what();
  }
  log_.add(record_message_);
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &color_rbo_);
  fbo_ = color_rbo_ = 0;
}

}  // namespace periflex
