// The window's input over the picture (not over the panels): the keys, the view's zoom and pan,
// the mouse spring's grab and drag (Shift: a hard grip), the knife, the body clicked to inspect.
#include "app/gui_app.h"
#include "app/playback_source.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/gui_app_shared.h"
#include "app/key_presses.h"
#include "app/picking.h"

namespace periflex {

namespace {
using gui_parts::kPickPixels;
// a magnification as the log writes it: "100", "0.5"
std::string format_deform(float factor) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(factor));
  return text;
}
}  // namespace

void GuiApp::handle_input(int fb_width, int fb_height) {
  ImGuiIO& io = ImGui::GetIO();
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
        send(SimCommand{command::ScrubStep{command::ScrubStep::Direction::kForward}, "key"});
      } else {
        send(SimCommand{command::Step{}, "key"});
      }
    }
    if (k.key == GLFW_KEY_LEFT) {
      send(SimCommand{command::ScrubStep{command::ScrubStep::Direction::kBack}, "key"});
    }
    if (k.repeat) continue;
    if (k.key == GLFW_KEY_SPACE) send(SimCommand{command::ToggleRun{}, "key"});
    if (k.key == GLFW_KEY_BACKSPACE) send(SimCommand{command::Reset{}, "key"});
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
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      grabbing_ = false;
      send(SimCommand{command::MouseSpring{}, "mouse"});
    } else if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f || io.KeyShift != grab_spring_.hard) {
      grab_spring_.target = world;
      grab_spring_.hard = io.KeyShift;
      send(SimCommand{command::MouseSpring{grab_spring_, false}, "mouse"});
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
      send(SimCommand{command::MouseSpring{spring, true}, "mouse"});
    }
  }
}

}  // namespace periflex
