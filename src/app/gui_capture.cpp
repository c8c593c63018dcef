// What leaves the window for outside eyes: the screenshot read from the back buffer, and the
// state of the window written each frame for the tests that drive it with real input
// (widget_dump.h).
#include "app/gui_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "app/gui_app_shared.h"
#include "app/picking.h"
#include "io/image.h"
#include "render/gl.h"

namespace periflex {

namespace {
using gui_parts::kPickPixels;
}  // namespace

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

}  // namespace periflex
