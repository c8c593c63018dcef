// The window's script runner (--script): each action at its frame, waits and expectations that
// block the script until the simulation reaches them (or fail it after a time limit), grabs
// aimed at world points, and the checks a scripted test asserts on.
#include "app/gui_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/gui_app_shared.h"
#include "app/picking.h"
#include "core/error.h"

namespace periflex {

namespace {
using gui_parts::kPickPixels;
using gui_parts::wall_seconds;
// a wait or expectation that takes longer than this (wall seconds) fails the script
constexpr double kScriptTimeout = 120.0;
}  // namespace

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
  const std::string& verb = a.verb;
  const auto send_action = [this](SimAction action) { send(SimCommand{std::move(action), "script"}); };
  log_.add("script @" + std::to_string(a.frame) + ": " + a.text);
  if (verb == "run" || verb == "resume") send_action(command::Run{});
  else if (verb == "pause") send_action(command::Pause{});
  else if (verb == "step") {
    send_action(command::Step{a.args.empty() ? 1 : std::atoi(a.args[0].c_str())});
  } else if (verb == "history") {
    const int budget_mb =
        a.args.size() > 1 ? std::atoi(a.args[1].c_str()) : static_cast<int>(status_.history_budget >> 20);
    send_action(command::History{std::atof(a.args[0].c_str()), budget_mb});
  } else if (verb == "back") {
    for (int k = a.args.empty() ? 1 : std::atoi(a.args[0].c_str()); k > 0; --k)
      send_action(command::ScrubStep{command::ScrubStep::Direction::kBack});
  } else if (verb == "scrub") {
    send_action(command::Scrub{std::atof(a.args[0].c_str())});
  } else if (verb == "reset") send_action(command::Reset{});
  else if (verb == "reload") send_action(command::Reload{});
  else if (verb == "scene") {
    send_action(command::LoadScene{resolve_scene_path(a.args[0])});
  } else if (verb == "set") {
    const size_t eq = a.args[0].find('=');
    send_action(command::SetParameter{a.args[0].substr(0, eq), a.args[0].substr(eq + 1)});
  } else if (verb == "speed") {
    send_action(command::SetSpeed{a.args[0] == "max" ? 0.0 : std::atof(a.args[0].c_str())});
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
    send_action(command::MouseSpring{grab_spring_, false});  // a move, not a new grab
  } else if (verb == "release") {
    grabbing_ = false;
    send_action(command::MouseSpring{});
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
    send_action(command::Cut{knife_from_, knife_to_, renderer_->drawn_x(), renderer_->drawn_y()});
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
  send(SimCommand{command::MouseSpring{spring, true}, "script"});
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

}  // namespace periflex
