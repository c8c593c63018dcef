// The visualiser's main-thread side: window, input, script, drawing and capture.
// Internal to src/app/; run_gui (gui.h) is the public entry point.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/event_log.h"
#include "app/file_watch.h"
#include "app/gui.h"
#include "app/gui_script.h"
#include "render/plot_history.h"
#include "app/sim_worker.h"
#include "app/view_fit.h"
#include "app/widget_dump.h"
#include "render/camera.h"
#include "io/background_frame_writer.h"
#include "io/frame_writer.h"
#include "io/image.h"
#include "render/renderer.h"
#include "render/view.h"

struct GLFWwindow;

namespace periflex {

class PlaybackSource;

// The deformation slider's largest factor (render/deformation.h: the automatic one stops at 1000).
constexpr double kMaxDeformSlider = 1000.0;

class GuiApp {
 public:
  GuiApp(const GuiOptions& options, std::vector<ScriptAction> script, EventLog& log, SimWorker& worker,
         GLFWwindow* window, const std::string& resource_root);
  ~GuiApp();
  // Runs the frame loop until the window closes, the script quits or --frames are drawn.
  // Returns the exit code of the visual part (0, or 1 for a failed expectation or capture).
  int run();
  // A replay's controls (`periflex play`): its timeline window and the Left key.
  void attach_playback(PlaybackSource* playback) { playback_ = playback; }

 private:
  // one frame
  void take_snapshot();
  bool run_script();
  bool script_blocked();
  void execute(const ScriptAction& action);
  void evaluate_expectation(const ScriptAction& action);
  void grab(const ScriptAction& action);
  void handle_input(int fb_width, int fb_height);
  void draw_panels(int fb_width, int fb_height);
  void capture_screenshot(const std::string& path, int fb_width, int fb_height);
  void send(SimCommand command);
  void script_failure(const std::string& what);
  void dump_state(int fb_width, int fb_height);
  // the mouse's grip (gui_grip.cpp): the spring to its anchor, the pointer it walks to, the pull
  // and its limits; and, for input-driven tests, the grip and the damage it did
  void draw_mouse_spring(const Snapshot& snap, int fb_width, int fb_height);
  void dump_grip_state(const Snapshot& snap);
  // the knife (gui_knife.cpp): a left-drag over the picture draws a segment; its release cuts
  void knife_input(const Vec2& world);
  void draw_knife(int fb_width, int fb_height);

  // panels (gui_panels.cpp)
  void panel_simulation();
  void panel_parameters();
  void panel_view();
  void panel_view_controls();
  void panel_deformation();
  void panel_description();
  // the history timeline, resume, cadence and budget (gui_history.cpp)
  void panel_history();

  // teaching aids (gui_teach.cpp)
  void help_window(int fb_width, int fb_height);
  void draw_performance(int fb_width);
  void watch_scene_file();
  void draw_load_error(int fb_width);
  // the particle under the pointer (gui_inspect.cpp)
  void inspect_particle(int fb_width, int fb_height);
  // the rigid body last clicked (gui_body_inspector.cpp)
  void inspect_body(int fb_width);
  void panel_plots();
  // the plot window (gui_plot.cpp) and its PNG, read from the frame just drawn
  void plot_window(int fb_width, int fb_height);
  // The plot window's series against its x column, the cursor at `cursor_time`; the x range is
  // the caller's (the window's zoom, or a recording's rows)
  PlotView plot_view(double cursor_time) const;
  void capture_plot(int fb_width, int fb_height);
  void panel_export();
  void panel_log();
  void numerical_error_modal();
  // a dt refused for the explicit stability limit: confirm to run it anyway (gui_panels.cpp)
  void unstable_step_modal();

  // recording (gui_record.cpp)
  void start_recording(const std::string& path, double interval, double fps, int fb_width, int fb_height);
  void stop_recording();
  // carries out what panels, keys and the script asked for during the frame, outside the
  // locked ImGui frame (the recorder's own ImGui context takes the same lock)
  void run_pending_actions(int fb_width, int fb_height);
  void pump_recording();
  void write_recorded_frame(const Snapshot& frame, FrameWriter& writer);
  // pictures without the panels, as recorded frames and screenshots show them; with the plot
  // window open, its plot over the picture from `rows`
  RgbaImage draw_picture(const Snapshot& frame, const Camera& camera, unsigned fbo, int width, int height,
                         const PlotHistory& rows);
  static bool make_target(int width, int height, unsigned& fbo, unsigned& rbo);
  void write_picture(const std::string& path, int fb_width, int fb_height);

  std::string default_screenshot_name() const;
  std::string resolve_scene_path(const std::string& path) const;
  std::vector<std::string> list_scenes() const;

  GuiOptions options_;
  PlaybackSource* playback_ = nullptr;
  std::vector<ScriptAction> script_;
  EventLog& log_;
  SimWorker& worker_;
  GLFWwindow* window_;
  std::string resource_root_;
  std::unique_ptr<Renderer> renderer_;

  // what is shown
  WorkerStatus status_;
  RenderSettings render_;
  Camera camera_;
  bool fit_pending_ = true;
  bool auto_frame_ = false;         // the view grows with the scene until the user moves it
  Framing framing_;                 // what the view frames while auto_frame_
  int follow_ = -1;                 // geometry body index, -1: none
  float deform_before_off_ = kAutoDeform;  // the magnification the D key brings back
  bool show_help_ = false;          // the F1 window
  std::string description_;         // of the scene shown (app/scene_description.h)
  std::string shown_scene_path_;    // the file it came from; reloading it keeps the camera
  FileWatch scene_watch_;           // that file, for the hot reload
  std::vector<FileWatch> geometry_watches_;  // the point files, images and drawings it reads
  double frame_seconds_ = 0.0, last_frame_wall_ = 0.0;
  PlotHistory history_;
  bool show_plot_ = false;          // the plot window (P)
  std::string plot_x_ = "t", plot_y_ = "kinetic";  // series.csv columns plotted
  std::vector<std::string> plot_more_;              // further series beside plot_y_, same x
  bool plot_zoomed_ = false;        // false: x spans the whole history
  double plot_x_lo_ = 0.0, plot_x_hi_ = 1.0;
  char plot_path_[512] = "plot";    // exports go to <this>.csv and <this>.png
  std::string plot_message_;
  std::string pending_plot_png_;    // asked this frame, read after drawing
  std::array<float, 4> plot_png_rect_{};  // the canvas in framebuffer pixels (x0, y0, x1, y1)
  long seen_generation_ = -1, seen_scene_generation_ = -1;
  LiveSettings edit_;               // the live-parameter panel's copy
  // a typed dt sent as command number `sent`: if refused for the stability limit, the window
  // asks whether to run it anyway (unstable_asked_ holds it while the question is open)
  struct UnstableOffer {
    LiveSettings settings;
    long sent = 0;
  };
  std::optional<UnstableOffer> unstable_offer_;
  LiveSettings unstable_asked_;
  long edit_generation_ = -1;
  int speed_choice_ = 0;
  int step_count_ = 100;            // the Simulation panel's "Step N"
  double history_interval_ = 0.0;   // the History panel's cadence and budget being typed
  int history_budget_mb_ = 256;
  bool history_edited_ = false;     // a field has the keyboard: not refreshed from the status
  long history_edit_generation_ = -1;
  double step_to_time_ = 0.0;       // its "Step to t"; 0: not set yet
  std::vector<std::string> scenes_;
  int scene_choice_ = -1;
  long shown_error_step_ = -2;      // the numerical failure last shown in the modal
  long log_shown_ = 0;              // log lines the panel has scrolled to

  WidgetDump dump_;                 // control positions and state for input-driven tests

  // script and frame count
  long frame_ = 0;
  size_t next_action_ = 0;
  std::optional<double> wait_time_;
  std::optional<ScriptAction> pending_expect_;   // an expect or grab waiting for the sync
  double block_started_ = 0.0;
  long sent_ = 0;
  bool quit_ = false;
  int exit_code_ = 0;

  // mouse
  bool knife_ = false;              // the knife mode (K): a left-drag cuts instead of grabbing
  bool cutting_ = false;            // a knife drag in progress, from knife_from_ to knife_to_
  Vec2 knife_from_ = Vec2::Zero(), knife_to_ = Vec2::Zero();
  int inspected_body_ = -1;         // geometry index of the rigid body clicked, -1: none
  bool reactions_asked_ = false;    // the simulation thread was asked for the reactions
  bool grabbing_ = false;
  bool grab_by_mouse_ = false;      // false: a script holds the grab
  MouseSpring grab_spring_;

  // capture and recording; panels and keys only record requests (pending_*), carried out by
  // run_pending_actions between frames
  struct RecordRequest {
    std::string path;
    double interval = 0.0;
    double fps = 30.0;
    std::string origin;             // "ui" or "script", for the log and script failures
  };
  std::optional<RecordRequest> pending_record_start_;
  bool pending_record_stop_ = false;
  std::string pending_screenshot_;
  std::string pending_picture_;     // a screenshot without the panels, drawn between frames
  bool screenshot_with_panels_ = false;
  char screenshot_path_[512] = "";
  char record_path_[512] = "frames";
  double record_interval_ = 0.0;
  float record_fps_ = 30.0f;
  std::unique_ptr<BackgroundFrameWriter> writer_;
  unsigned fbo_ = 0, color_rbo_ = 0;
  Camera record_camera_;
  PlotHistory record_rows_;         // the recorded frames' series rows, for the plot over them
  int record_width_ = 0, record_height_ = 0;
  std::string record_message_;
};

}  // namespace periflex
