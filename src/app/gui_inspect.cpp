// The particle under the pointer, inspected: a tooltip with its id and body, position,
// displacement, velocity, damage, bonds intact and broken, and largest bond stretch. It is
// found where it is drawn (magnified or not), so what the eye points at is what is shown.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/gui_app.h"
#include "app/picking.h"

namespace periflex {

namespace {

// pixels within which the pointer inspects a particle (as the mouse grabs one)
constexpr double kInspectPixels = 6.0;

// value i of v, 0 when v is shorter (a snapshot without that field)
template <class T>
double at_or_zero(const std::vector<T>& v, int i) {
  return i >= 0 && static_cast<size_t>(i) < v.size() ? static_cast<double>(v[i]) : 0.0;
}

}  // namespace

void GuiApp::inspect_particle(int fb_width, int fb_height) {
  const ImGuiIO& io = ImGui::GetIO();
  // only over the picture, and not while the mouse holds something or cuts
  if (io.WantCaptureMouse || grabbing_ || cutting_ || !worker_.has_snapshot()) return;
  const Snapshot& snap = worker_.snapshot();
  if (!snap.geometry || !snap.geometry->has_particles()) return;
  int win_w = 1, win_h = 1;
  glfwGetWindowSize(window_, &win_w, &win_h);
  const double sx = double(fb_width) / std::max(1, win_w), sy = double(fb_height) / std::max(1, win_h);
  const Vec2 world = camera_.to_world(io.MousePos.x * sx, io.MousePos.y * sy, fb_width, fb_height);
  const double tolerance = kInspectPixels * camera_.view_height / std::max(1, fb_height);
  const int i = particle_at(snap, renderer_->drawn_x(), renderer_->drawn_y(), world, tolerance);
  if (i < 0 || static_cast<size_t>(i) >= snap.px.size()) return;

  // which body, and the particle's place in it
  const SceneGeometry& g = *snap.geometry;
  std::string body;
  for (const auto& fb : g.flex_bodies)
    if (i >= fb.first_particle && i < fb.first_particle + fb.particle_count) body = fb.name;
  const double x = snap.px[i], y = snap.py[i];
  const double ux = x - at_or_zero(g.reference_x, i), uy = y - at_or_zero(g.reference_y, i);
  const double vx = at_or_zero(snap.vx, i), vy = at_or_zero(snap.vy, i);
  const int initial = static_cast<int>(at_or_zero(g.bonds_initial, i));
  const int intact = static_cast<int>(at_or_zero(snap.bonds_intact, i));

  ImGui::BeginTooltip();
  ImGui::Text("particle %d (%s)", i, body.c_str());
  dump_.note_item("inspector");
  ImGui::Separator();
  ImGui::Text("position      %.6g, %.6g m", x, y);
  ImGui::Text("displacement  %.4g, %.4g m (|u| %.4g)", ux, uy, std::hypot(ux, uy));
  ImGui::Text("velocity      %.4g, %.4g m/s (|v| %.4g)", vx, vy, std::hypot(vx, vy));
  ImGui::Text("damage        %.3f", at_or_zero(snap.damage, i));
  ImGui::Text("bonds         %d intact, %d broken", intact, std::max(0, initial - intact));
  ImGui::Text("largest bond stretch %.4g", at_or_zero(snap.strain, i));
  if (i < static_cast<int>(g.particle_attached.size()) && g.particle_attached[i])
    ImGui::TextDisabled("held by a rigid-flexible joint");
  ImGui::EndTooltip();
  char text[96];
  std::snprintf(text, sizeof text, "%d %d %d", i, intact, std::max(0, initial - intact));
  dump_.state("inspected", text);
}

}  // namespace periflex
