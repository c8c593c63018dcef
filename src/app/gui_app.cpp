// The window: one frame after another (snapshot and status of the frame, the camera, the picture,
// the panels, what the script and the input asked for), the scene list and the commands sent to
// the simulation thread. The script runner, the input and the capture are beside it
// (gui_script_runner.cpp, gui_input.cpp, gui_capture.cpp); the panels in gui_panels.cpp.
#include "app/gui_app.h"
#include "app/playback_source.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "app/gui_app_shared.h"
#include "app/scene_description.h"
#include "app/view_fit.h"
#include "render/gl.h"

namespace periflex {

namespace fs = std::filesystem;

namespace {
using gui_parts::wall_seconds;
}  // namespace

GuiApp::GuiApp(const GuiOptions& options, std::vector<ScriptAction> script, EventLog& log, SimWorker& worker,
               GLFWwindow* window, const std::string& resource_root)
    : options_(options), script_(std::move(script)), log_(log), worker_(worker), window_(window),
      resource_root_(resource_root) {
  renderer_ = std::make_unique<Renderer>(resource_root_);
  render_.deform = static_cast<float>(options_.deform < 0.0 ? kAutoDeform : options_.deform);
  scenes_ = list_scenes();
}

GuiApp::~GuiApp() { stop_recording(); }

void GuiApp::send(SimCommand command) {
  ++sent_;
  worker_.send(std::move(command));
}

void GuiApp::script_failure(const std::string& what) {
  log_.add("script: " + what);
  exit_code_ = kExitOther;
}

std::string GuiApp::resolve_scene_path(const std::string& path) const {
  // as given, else relative to the shipped scenes
  if (fs::exists(path)) return path;
  const fs::path shipped = fs::path(resource_root_) / "scenes" / path;
  if (fs::exists(shipped)) return shipped.string();
  return path;
}

std::vector<std::string> GuiApp::list_scenes() const {
  // the runnable scenes: scenes/*.toml (the studies' and stability checks' files in the
  // folders below are inputs of `periflex study` and `periflex stability`, not scenes to open)
  std::vector<std::string> out;
  const fs::path root = fs::path(resource_root_) / "scenes";
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return out;
  for (auto it = fs::directory_iterator(root, ec); it != fs::directory_iterator(); ++it) {
    if (it->is_regular_file() && it->path().extension() == ".toml") out.push_back(it->path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string GuiApp::default_screenshot_name() const {
  char name[160];
  std::snprintf(name, sizeof name, "periflex_%s_t%.6g.png",
                status_.scene_name.empty() ? "scene" : status_.scene_name.c_str(), status_.time);
  std::string s = name;
  std::replace(s.begin(), s.end(), ' ', '_');
  return s;
}

// ---------------------------------------------------------------------------------------------
// snapshot and status of this frame

void GuiApp::take_snapshot() {
  // status first: a snapshot is published before the status describing it, so the snapshot
  // taken next is at least as new as the status (a script acting on the status sees its state)
  status_ = worker_.status();
  worker_.update_snapshot();
  const Snapshot& snap = worker_.snapshot();
  // a rebuilt model starts new plots; a scene loaded from disk is framed again
  if (status_.generation != seen_generation_) {
    history_.clear();
    renderer_->clear_trails();
    seen_generation_ = status_.generation;
  }
  if (status_.scene_generation != seen_scene_generation_) {
    seen_scene_generation_ = status_.scene_generation;
    glfwSetWindowTitle(window_, ("periflex - " + status_.scene_name).c_str());
    // a new scene is framed; the same file read again (Reload, or saved on disk) keeps the view
    if (status_.scene_path != shown_scene_path_) {
      fit_pending_ = true;
      follow_ = -1;
      inspected_body_ = -1;
    }
    shown_scene_path_ = status_.scene_path;
    description_ = scene_description(status_.scene_path, status_.scene_description);
    scene_watch_.watch(status_.scene_path, wall_seconds());
    geometry_watches_.assign(status_.geometry_files.size(), FileWatch());
    for (size_t k = 0; k < geometry_watches_.size(); ++k)
      geometry_watches_[k].watch(status_.geometry_files[k], wall_seconds());
    const auto found = std::find(scenes_.begin(), scenes_.end(),
                                 fs::path(status_.scene_path).filename().string());
    scene_choice_ = found == scenes_.end() ? -1 : static_cast<int>(found - scenes_.begin());
  }
  // a state from the history shown: the plots and trails after it are of a future to be recomputed
  if (worker_.has_snapshot() && history_.size() > 0 && snap.time < history_.last_time()) {
    history_.drop_from(snap.time);
    renderer_->clear_trails();
  }
  if (worker_.has_snapshot()) history_.add(snap, status_.steps_per_second);
}

// ---------------------------------------------------------------------------------------------
// the frame loop

void GuiApp::run_pending_actions(int fb_width, int fb_height) {
  // a stop asked in the same frame as a start applies to the recording running before it
  if (pending_record_stop_) {
    pending_record_stop_ = false;
    stop_recording();
  }
  if (!pending_picture_.empty()) {
    write_picture(pending_picture_, fb_width, fb_height);
    pending_picture_.clear();
  }
  if (pending_record_start_) {
    const RecordRequest r = *pending_record_start_;
    pending_record_start_.reset();
    start_recording(r.path, r.interval, r.fps, fb_width, fb_height);
    if (!writer_ && r.origin == "script") script_failure("recording did not start: " + record_message_);
  }
}

int GuiApp::run() {
  for (;;) {
    glfwPollEvents();
    if (glfwWindowShouldClose(window_)) break;
    if (const int signal_number = options_.interrupt ? options_.interrupt() : 0) {
      exit_code_ = 128 + signal_number;
      break;
    }
    take_snapshot();
    watch_scene_file();
    const bool advance = run_script();
    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window_, &fb_width, &fb_height);
    if (fb_width <= 0 || fb_height <= 0) {  // minimised: nothing to draw
      glfwWaitEventsTimeout(0.05);
      continue;
    }
    const Snapshot& snap = worker_.snapshot();

    // the last frame of a --frames run is the screenshot
    const bool last_frame = options_.frames > 0 && advance && frame_ + 1 >= options_.frames;
    if (last_frame && !options_.screenshot.empty()) pending_screenshot_ = options_.screenshot;
    // the whole window (screenshot_ui) is read from it; a picture is drawn off-screen after it
    const std::string screenshot = screenshot_with_panels_ ? pending_screenshot_ : std::string();
    if (!screenshot_with_panels_ && !pending_screenshot_.empty()) pending_picture_ = pending_screenshot_;
    pending_screenshot_.clear();
    screenshot_with_panels_ = false;

    // recorded frames first: they draw into their own framebuffer
    pump_recording();

    {
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      dump_.begin_frame();
      handle_input(fb_width, fb_height);

      // camera: fit when asked (and once there is something to fit), follow a body
      if (fit_pending_ && snap.geometry) {
        framing_ = start_framing(snap);
        camera_ = fit_camera_beside_panels(framing_.shown, fb_width, fb_height, kPanelWidth);
        fit_pending_ = false;
        auto_frame_ = true;
      }
      // until the user moves the view, it grows to keep what moves in sight
      // (not while recording: a movie keeps the camera it started with)
      if (auto_frame_ && follow_ <= 0 && !writer_ && snap.geometry && grow_framing(framing_, snap)) {
        camera_ = fit_camera_beside_panels(framing_.shown, fb_width, fb_height, kPanelWidth);
      }
      if (follow_ > 0 && follow_ < static_cast<int>(snap.bodies.size())) {
        camera_.center = Vec2(snap.bodies[follow_].x, snap.bodies[follow_].y);
      }

      // the picture; a drawing failure (say, a missing colour map) is shown, not fatal
      try {
        if (snap.geometry) {
          renderer_->draw(snap, camera_, render_, fb_width, fb_height);
          // the overlay beside the panel column; the panels are drawn over the picture after it
          renderer_->draw_overlay(snap, render_, fb_width, fb_height, kPanelWidth);
        }
      } catch (const std::exception& e) {
        log_.add(std::string("drawing failed: ") + e.what() + "; back to the default colour map");
        render_.colormap = RenderSettings{}.colormap;
      }
      draw_mouse_spring(snap, fb_width, fb_height);
      draw_knife(fb_width, fb_height);
      draw_panels(fb_width, fb_height);
      if (playback_) playback_->draw(worker_, dump_, fb_width, fb_height, kPanelWidth);
      draw_performance(fb_width);
      plot_window(fb_width, fb_height);
      inspect_particle(fb_width, fb_height);
      inspect_body(fb_width);
      draw_load_error(fb_width);
      help_window(fb_width, fb_height);
      dump_state(fb_width, fb_height);
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      dump_.end_frame();
    }
    if (!screenshot.empty()) capture_screenshot(screenshot, fb_width, fb_height);
    if (!pending_plot_png_.empty()) capture_plot(fb_width, fb_height);
    glfwSwapBuffers(window_);
    run_pending_actions(fb_width, fb_height);

    if (advance) ++frame_;
    if (quit_ || (options_.frames > 0 && frame_ >= options_.frames)) break;
    // a script waiting on the simulation need not redraw flat out (no vsync in scripted runs)
    if (!advance) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  stop_recording();
  return exit_code_;
}

}  // namespace periflex
