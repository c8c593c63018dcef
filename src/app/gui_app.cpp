#include "app/gui_app.h"
#include "app/playback_source.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>

#include "app/key_presses.h"
#include "app/picking.h"
#include "app/scene_description.h"
#include "app/view_fit.h"
#include "core/error.h"
#include "core/resources.h"
#include "render/gl.h"
#include "io/image.h"

namespace periflex {

namespace fs = std::filesystem;

namespace {

// a wait or expectation that takes longer than this (wall seconds) fails the script
constexpr double kScriptTimeout = 120.0;
// pixels within which the mouse grabs a particle
constexpr double kPickPixels = 6.0;

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// a magnification as the log writes it: "100", "0.5"
std::string format_deform(float factor) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(factor));
  return text;
}


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
// script

bool GuiApp::script_blocked() {
  if (!wait_time_ && !pending_expect_) return false;
  // the simulation thread must have applied everything sent before the condition is judged
  const bool synced = status_.commands_applied >= sent_;
  const bool timed_out = wall_seconds() - block_started_ > kScriptTimeout;
  if (wait_time_) {
    if (synced && (status_.time >= *wait_time_ || !status_.running)) {
      log_.add("script: wait ended at t = " + std::to_string(status_.time));
      wait_time_.reset();
    } else if (timed_out) {
      script_failure("wait for t = " + std::to_string(*wait_time_) + " timed out at t = " +
                     std::to_string(status_.time));
      wait_time_.reset();
    }
    return wait_time_.has_value();
  }
  if (synced) {
    const ScriptAction a = *pending_expect_;
    pending_expect_.reset();
    if (a.verb == "grab") grab(a);
    else evaluate_expectation(a);
    return false;
  }
  if (timed_out) {
    script_failure("'" + pending_expect_->text + "' timed out waiting for the simulation thread");
    pending_expect_.reset();
  }
  return pending_expect_.has_value();
}

bool GuiApp::run_script() {
  for (;;) {
    if (script_blocked()) return false;
    if (next_action_ >= script_.size() || script_[next_action_].frame > frame_) return true;
    execute(script_[next_action_++]);
  }
}

void GuiApp::execute(const ScriptAction& a) {
  using Kind = SimCommand::Kind;
  const std::string& verb = a.verb;
  const auto command = [](Kind kind) { return SimCommand::make(kind, "script"); };
  log_.add("script @" + std::to_string(a.frame) + ": " + a.text);
  if (verb == "run" || verb == "resume") send(command(Kind::kRun));
  else if (verb == "pause") send(command(Kind::kPause));
  else if (verb == "step") {
    SimCommand c = command(Kind::kStep);
    c.count = a.args.empty() ? 1 : std::atoi(a.args[0].c_str());
    send(c);
  } else if (verb == "history") {
    SimCommand c = command(Kind::kHistory);
    c.number = std::atof(a.args[0].c_str());
    c.count = a.args.size() > 1 ? std::atoi(a.args[1].c_str()) : static_cast<int>(status_.history_budget >> 20);
    send(c);
  } else if (verb == "back") {
    SimCommand c = command(Kind::kScrubStep);
    c.count = -1;
    for (int k = a.args.empty() ? 1 : std::atoi(a.args[0].c_str()); k > 0; --k) send(c);
  } else if (verb == "scrub") {
    SimCommand c = command(Kind::kScrub);
    c.number = std::atof(a.args[0].c_str());
    send(c);
  } else if (verb == "reset") send(command(Kind::kReset));
  else if (verb == "reload") send(command(Kind::kReload));
  else if (verb == "scene") {
    SimCommand c = command(Kind::kLoadScene);
    c.text = resolve_scene_path(a.args[0]);
    send(c);
  } else if (verb == "set") {
    const size_t eq = a.args[0].find('=');
    SimCommand c = command(Kind::kSetParameter);
    c.text = a.args[0].substr(0, eq);
    c.value = a.args[0].substr(eq + 1);
    send(c);
  } else if (verb == "speed") {
    SimCommand c = command(Kind::kSetSpeed);
    c.number = a.args[0] == "max" ? 0.0 : std::atof(a.args[0].c_str());
    send(c);
  } else if (verb == "colormap") {
    const auto names = renderer_->colormap_names();
    if (std::find(names.begin(), names.end(), a.args[0]) == names.end()) {
      script_failure("unknown colour map '" + a.args[0] + "'");
    } else {
      render_.colormap = a.args[0];
    }
  } else if (verb == "field") {
    parse_field_name(a.args[0], render_.field);
  } else if (verb == "range") {
    render_.auto_range = a.args[0] == "auto";
    if (!render_.auto_range) {
      render_.range_min = static_cast<float>(std::atof(a.args[0].c_str()));
      render_.range_max = static_cast<float>(std::atof(a.args[1].c_str()));
    }
  } else if (verb == "show") {
    const bool on = a.args[1] == "on";
    const std::string& layer = a.args[0];
    if (layer == "bodies") render_.show_bodies = on;
    else if (layer == "markers") render_.show_markers = on;
    else if (layer == "springs") render_.show_springs = on;
    else if (layer == "bonds") render_.show_bonds = on;
    else if (layer == "probes") render_.show_probes = on;
    else if (layer == "trails") render_.show_trails = on;
    else if (layer == "contacts") render_.show_contacts = on;
    else render_.show_overlay = on;
  } else if (verb == "fit") {
    fit_pending_ = true;
    follow_ = -1;
  } else if (verb == "follow") {
    follow_ = -1;
    const Snapshot& s = worker_.snapshot();
    if (a.args[0] != "none" && s.geometry) {
      for (size_t b = 1; b < s.geometry->bodies.size(); ++b) {
        if (s.geometry->bodies[b].name == a.args[0]) follow_ = static_cast<int>(b);
      }
      if (follow_ < 0) script_failure("no rigid body named '" + a.args[0] + "' to follow");
    }
  } else if (verb == "screenshot") {
    pending_screenshot_ = a.args[0];
  } else if (verb == "screenshot_ui") {
    pending_screenshot_ = a.args[0];
    screenshot_with_panels_ = true;
  } else if (verb == "record") {
    pending_record_start_ = RecordRequest{a.args[0], std::atof(a.args[1].c_str()), record_fps_, "script"};
  } else if (verb == "stop_record") {
    pending_record_stop_ = true;
  } else if (verb == "grab") {
    // after the requests sent so far (a reset, say) have been applied
    pending_expect_ = a;
    block_started_ = wall_seconds();
  } else if (verb == "drag") {
    if (!grabbing_) {
      script_failure("drag without a grab");
      return;
    }
    grab_spring_.target = Vec2(std::atof(a.args[0].c_str()), std::atof(a.args[1].c_str()));
    SimCommand c = command(Kind::kMouseSpring);
    c.spring = grab_spring_;
    c.count = 0;  // a move, not a new grab
    send(c);
  } else if (verb == "release") {
    grabbing_ = false;
    send(command(Kind::kMouseSpring));
  } else if (verb == "plot") {
    // the plot window with column Y (Y1+Y2+...: several series, as "+ series" adds them)
    // against X (time by default); a column the scene lacks falls back as in the window
    show_plot_ = true;
    plot_more_.clear();
    std::string columns = a.args[0];
    for (size_t plus; (plus = columns.rfind('+')) != std::string::npos; columns.resize(plus))
      plot_more_.insert(plot_more_.begin(), columns.substr(plus + 1));
    plot_y_ = columns;
    plot_x_ = a.args.size() > 1 ? a.args[1] : "t";
    plot_zoomed_ = false;
  } else if (verb == "cut") {
    // the knife from (X0, Y0) to (X1, Y1), as a mouse drag cuts
    knife_from_ = Vec2(std::atof(a.args[0].c_str()), std::atof(a.args[1].c_str()));
    knife_to_ = Vec2(std::atof(a.args[2].c_str()), std::atof(a.args[3].c_str()));
    SimCommand c = command(Kind::kCut);
    c.from = knife_from_;
    c.to = knife_to_;
    c.drawn_x = renderer_->drawn_x();
    c.drawn_y = renderer_->drawn_y();
    send(std::move(c));
  } else if (verb == "inspect") {
    inspected_body_ = -1;
    const Snapshot& s = worker_.snapshot();
    if (a.args[0] != "none" && s.geometry) {
      for (size_t b = 1; b < s.geometry->bodies.size(); ++b) {
        if (s.geometry->bodies[b].name == a.args[0]) inspected_body_ = static_cast<int>(b);
      }
      if (inspected_body_ < 0) script_failure("no rigid body named '" + a.args[0] + "' to inspect");
    }
  } else if (verb == "wait") {
    wait_time_ = std::atof(a.args[0].c_str());
    block_started_ = wall_seconds();
  } else if (verb == "expect") {
    pending_expect_ = a;
    block_started_ = wall_seconds();
  } else if (verb == "quit") {
    quit_ = true;
  }
}

void GuiApp::grab(const ScriptAction& a) {
  // what lies at the world point, picked as the mouse would
  const Vec2 world(std::atof(a.args[0].c_str()), std::atof(a.args[1].c_str()));
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window_, &fb_width, &fb_height);
  const double tolerance = kPickPixels * camera_.view_height / std::max(1, fb_height);
  std::optional<MouseSpring> spring = pick(worker_.snapshot(), world, tolerance);
  if (!spring) {
    script_failure("nothing to grab at (" + a.args[0] + ", " + a.args[1] + ")");
    return;
  }
  grabbing_ = true;
  grab_by_mouse_ = false;
  grab_spring_ = *spring;
  SimCommand c = SimCommand::make(SimCommand::Kind::kMouseSpring, "script");
  c.spring = spring;
  c.count = 1;
  send(c);
}

void GuiApp::evaluate_expectation(const ScriptAction& a) {
  const std::string& what = a.args[0];
  std::string failure;
  if (what == "running" || what == "paused") {
    if (status_.running != (what == "running")) failure = std::string("the simulation is ") +
                                                         (status_.running ? "running" : "paused");
  } else if (what.find('=') != std::string::npos) {
    const std::string key = what.substr(0, what.find('='));
    const std::string value = what.substr(what.find('=') + 1);
    if (key == "colormap") {
      if (render_.colormap != value) failure = "colour map is " + render_.colormap;
    } else if (key == "scene") {
      if (status_.scene_name != value) failure = "scene is " + status_.scene_name;
    } else {
      // a live setting: setting the expected value on a copy must change nothing
      LiveSettings expected = status_.settings;
      const std::string problem = set_live_parameter(expected, key, value);
      if (!problem.empty()) failure = problem;
      else if (!same_live_settings(expected, status_.settings)) failure = key + " differs";
    }
  } else {
    failure = "cannot check '" + what + "'";
  }
  if (failure.empty()) log_.add("script: expectation '" + a.text + "' holds");
  else script_failure("expectation '" + a.text + "' failed: " + failure);
}

// ---------------------------------------------------------------------------------------------
// input: keys and mouse over the picture (not over panels)

void GuiApp::handle_input(int fb_width, int fb_height) {
  ImGuiIO& io = ImGui::GetIO();
  using Kind = SimCommand::Kind;
  // every press since the last frame, however short (key_presses.h); none while a text field
  // has the keyboard
  for (const KeyPress& k : take_key_presses()) {
    if (io.WantCaptureKeyboard) continue;
    const bool ctrl = (k.mods & GLFW_MOD_CONTROL) != 0;
    if (playback_ && playback_->on_key(k.key, worker_)) continue;
    // Right: one step, or one saved state forward while the history is shown; Left: one saved
    // state back (both repeat when held)
    if (k.key == GLFW_KEY_RIGHT) {
      if (status_.scrub >= 0) {
        SimCommand c = SimCommand::make(Kind::kScrubStep, "key");
        c.count = 1;
        send(c);
      } else {
        send(SimCommand::make(Kind::kStep, "key"));
      }
    }
    if (k.key == GLFW_KEY_LEFT) {
      SimCommand c = SimCommand::make(Kind::kScrubStep, "key");
      c.count = -1;
      send(c);
    }
    if (k.repeat) continue;
    if (k.key == GLFW_KEY_SPACE) send(SimCommand::make(Kind::kToggleRun, "key"));
    if (k.key == GLFW_KEY_BACKSPACE) send(SimCommand::make(Kind::kReset, "key"));
    if (k.key == GLFW_KEY_F && !ctrl) {
      fit_pending_ = true;
      follow_ = -1;
      log_.add("fit view (key)");
    }
    if (k.key == GLFW_KEY_S && !ctrl) pending_screenshot_ = default_screenshot_name();
    if (k.key == GLFW_KEY_F1) show_help_ = !show_help_;
    if (k.key == GLFW_KEY_P && !ctrl) show_plot_ = !show_plot_;
    if (k.key == GLFW_KEY_K && !ctrl) {
      knife_ = !knife_;
      cutting_ = false;
      log_.add(knife_ ? "knife on (key)" : "knife off (key)");
    }
    // D: the undeformed shape, and back to the magnification before
    if (k.key == GLFW_KEY_D && !ctrl) {
      if (render_.deform != 0.0f) {
        deform_before_off_ = render_.deform;
        render_.deform = 0.0f;
      } else {
        render_.deform = deform_before_off_;
      }
      log_.add(render_.deform == 0.0f ? std::string("view: deformation x0 (key)")
               : render_.deform < 0.0f ? std::string("view: deformation auto (key)")
                                       : "view: deformation x" + format_deform(render_.deform) + " (key)");
    }
    // C: draw the active contacts, or not
    if (k.key == GLFW_KEY_C && !ctrl) {
      render_.show_contacts = !render_.show_contacts;
      log_.add(std::string("view: contacts ") + (render_.show_contacts ? "on" : "off") + " (key)");
    }
    if (k.key == GLFW_KEY_Q && ctrl) {
      log_.add("quit (key)");
      quit_ = true;
    }
  }

  // window coordinates to framebuffer pixels (they differ on high-density screens)
  int win_w = 1, win_h = 1;
  glfwGetWindowSize(window_, &win_w, &win_h);
  const double sx = double(fb_width) / std::max(1, win_w), sy = double(fb_height) / std::max(1, win_h);
  const double mx = io.MousePos.x * sx, my = io.MousePos.y * sy;
  const Vec2 world = camera_.to_world(mx, my, fb_width, fb_height);

  // a grab lasts until the left button is released, wherever the mouse goes; Shift held makes
  // it a hard one (faster and stronger), taken or let go at any time during the drag
  if (grabbing_ && grab_by_mouse_) {
    SimCommand c = SimCommand::make(Kind::kMouseSpring, "mouse");
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      grabbing_ = false;
      send(c);
    } else if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f || io.KeyShift != grab_spring_.hard) {
      c.count = 0;
      grab_spring_.target = world;
      grab_spring_.hard = io.KeyShift;
      c.spring = grab_spring_;
      send(c);
    }
  }
  // a knife drag lasts until the button is released, wherever the mouse goes
  if (cutting_) knife_input(world);
  if (io.WantCaptureMouse) return;

  if (io.MouseWheel != 0.0f) {
    camera_.zoom_at(std::pow(1.15, io.MouseWheel), mx, my, fb_width, fb_height);
    auto_frame_ = false;
  }
  if (ImGui::IsMouseDown(ImGuiMouseButton_Right) && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    camera_.pan_pixels(io.MouseDelta.x * sx, io.MouseDelta.y * sy, fb_height);
    follow_ = -1;
    auto_frame_ = false;
  }
  if (knife_ && !cutting_ && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    cutting_ = true;
    knife_from_ = knife_to_ = world;
  } else if (!knife_ && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && worker_.has_snapshot()) {
    const double tolerance = kPickPixels * camera_.view_height / std::max(1, fb_height);
    std::optional<MouseSpring> spring = pick(worker_.snapshot(), world, tolerance);
    // a rigid body clicked is inspected (and held, as any body clicked); the empty picture
    // clicked closes the inspector
    inspected_body_ = spring && spring->body >= 0 ? spring->body + 1 : spring ? inspected_body_ : -1;
    if (spring) {
      spring->hard = io.KeyShift;
      grabbing_ = true;
      grab_by_mouse_ = true;
      grab_spring_ = *spring;
      SimCommand c = SimCommand::make(Kind::kMouseSpring, "mouse");
      c.spring = spring;
      c.count = 1;
      send(c);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// capture

void GuiApp::capture_screenshot(const std::string& path, int fb_width, int fb_height) {
  RgbaImage image;
  image.resize(fb_width, fb_height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  flip_rows(image);
  // the window's alpha channel is not part of the picture
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  try {
    write_png(path, image);
    log_.add("screenshot " + path + " (" + std::to_string(fb_width) + "x" + std::to_string(fb_height) +
             ", t = " + std::to_string(worker_.snapshot().time) + ")");
  } catch (const std::exception& e) {
    log_.add(std::string("screenshot failed: ") + e.what());
    if (options_.frames > 0) exit_code_ = kExitOther;
  }
}

// ---------------------------------------------------------------------------------------------
// the frame loop

void GuiApp::dump_state(int fb_width, int fb_height) {
  // what input-driven tests compare against (see widget_dump.h)
  if (!dump_.enabled()) return;
  dump_.state("running", status_.running ? "1" : "0");
  dump_.state("step", static_cast<double>(status_.step));
  dump_.state("time", status_.time);
  dump_.state("bond_damping", status_.settings.bond_damping);
  dump_.state("dt", status_.settings.dt);
  if (status_.numerical_error) dump_.state("numerical_error", status_.numerical_error->quantity);
  dump_.state("history_states", static_cast<double>(status_.history_states));
  dump_.state("history_interval", status_.history_interval);
  dump_.state("scrub", static_cast<double>(status_.scrub));
  {
    // the series row of the state shown, as a hash of its bits: equal rows, equal hashes
    uint64_t h = 0xcbf29ce484222325ull;
    for (double v : worker_.snapshot().series) {
      unsigned char bytes[sizeof v];
      std::memcpy(bytes, &v, sizeof v);
      for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ull;
    }
    char text[24];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    dump_.state("series_hash", text);
  }
  dump_.state("recording", writer_ ? "1" : "0");
  dump_.state("deform", renderer_->last_deform());
  dump_.state("deform_auto", render_.deform < 0.0f ? "1" : "0");
  dump_.state("help", show_help_ ? "1" : "0");
  dump_.state("knife", knife_ ? "1" : "0");
  dump_.state("broken_bonds", static_cast<double>(worker_.snapshot().broken_bonds));
  // each probe where it is now, "X Y" [m]
  for (const Snapshot::Probe& p : worker_.snapshot().probes) {
    char at[64];
    std::snprintf(at, sizeof at, "%.9g %.9g", p.position.x(), p.position.y());
    dump_.state("probe_" + p.name, at);
  }
  dump_.state("contacts", std::string(render_.show_contacts ? "1 " : "0 ") +
                              std::to_string(worker_.snapshot().contacts.size()));
  // the description's first line, which a test compares with the scene file's first comment
  dump_.state("description", description_.substr(0, description_.find('\n')));
  dump_.state("scene_generation", static_cast<double>(status_.scene_generation));
  if (!status_.load_error.empty()) dump_.state("load_error", status_.load_error.substr(0, status_.load_error.find('\n')));
  dump_.state("frames_written", writer_ ? static_cast<double>(writer_->frames_written()) : 0.0);
  int win_w = 1, win_h = 1;
  glfwGetWindowSize(window_, &win_w, &win_h);
  dump_.state("window", std::to_string(win_w) + " " + std::to_string(win_h));
  const double sx = double(fb_width) / std::max(1, win_w), sy = double(fb_height) / std::max(1, win_h);
  // world to window coordinates, so a test can aim at a world point:
  // window x = ax X + bx, window y = ay Y + by
  const Vec2 origin = camera_.to_pixels(Vec2(0.0, 0.0), fb_width, fb_height);
  const Vec2 unit = camera_.to_pixels(Vec2(1.0, 1.0), fb_width, fb_height);
  char mapping[160];
  std::snprintf(mapping, sizeof mapping, "%.9g %.9g %.9g %.9g", (unit.x() - origin.x()) / sx, origin.x() / sx,
                (unit.y() - origin.y()) / sy, origin.y() / sy);
  dump_.state("world_to_window", std::string(mapping));
  const Snapshot& snap = worker_.snapshot();
  const auto particle = [&snap](int i) {
    char text[80];
    std::snprintf(text, sizeof text, "%d %.9g %.9g", i, snap.px[i], snap.py[i]);
    return std::string(text);
  };
  if (grabbing_ && grab_spring_.particle >= 0 && grab_spring_.particle < static_cast<int>(snap.px.size())) {
    dump_.state("grabbed", particle(grab_spring_.particle));
  }
  dump_grip_state(snap);
  // the particle the left button would grab now
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const Vec2 world = camera_.to_world(mouse.x * sx, mouse.y * sy, fb_width, fb_height);
  const double tolerance = kPickPixels * camera_.view_height / std::max(1, fb_height);
  if (std::optional<MouseSpring> s = pick(snap, world, tolerance); s && s->particle >= 0) {
    dump_.state("pointed", particle(s->particle));
  }
}

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
