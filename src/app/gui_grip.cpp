// The mouse's grip in the window: the spring from what is held to its anchor, the anchor's walk
// to the pointer (solve/mouse_grip.h: it moves at a capped speed in simulated time and waits
// while the pull is at its limit), and the pull in newtons beside its limit.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "app/gui_app.h"

namespace periflex {

void GuiApp::draw_mouse_spring(const Snapshot& snap, int fb_width, int fb_height) {
  if (!grabbing_ || status_.mouse_stiffness <= 0.0) return;
  Vec2 held;
  if (grab_spring_.particle >= 0 && grab_spring_.particle < static_cast<int>(snap.px.size())) {
    held = Vec2(snap.px[grab_spring_.particle], snap.py[grab_spring_.particle]);
  } else if (grab_spring_.body >= 0 && grab_spring_.body + 1 < static_cast<int>(snap.bodies.size())) {
    const Snapshot::Pose& pose = snap.bodies[grab_spring_.body + 1];
    held = Vec2(pose.x, pose.y) + rotation(pose.angle) * grab_spring_.local_point;
  } else {
    return;
  }
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x > 0.0f ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  const auto window_point = [&](const Vec2& world) {
    const Vec2 p = camera_.to_pixels(world, fb_width, fb_height);
    return ImVec2(static_cast<float>(p.x()) / scale, static_cast<float>(p.y()) / scale);
  };
  // the anchor as the snapshot shows it (the pointer itself until the first snapshot of the grab)
  const Vec2 anchor_world = snap.mouse.held ? snap.mouse.anchor : grab_spring_.target;
  const ImVec2 a = window_point(held), anchor = window_point(anchor_world), pointer = window_point(grab_spring_.target);
  ImDrawList* list = ImGui::GetBackgroundDrawList();
  const ImU32 colour = IM_COL32(90, 220, 255, 255);
  const ImU32 faded = IM_COL32(90, 220, 255, 110);
  // the spring pulls what is held towards its anchor; the anchor walks along the faded line
  list->AddLine(anchor, pointer, faded, 1.0f);
  list->AddCircle(pointer, 6.0f, faded, 0, 1.5f);
  list->AddLine(a, anchor, colour, 2.0f);
  list->AddCircleFilled(a, 4.0f, colour);
  list->AddRect(ImVec2(anchor.x - 4.0f, anchor.y - 4.0f), ImVec2(anchor.x + 4.0f, anchor.y + 4.0f), colour, 0.0f, 0,
                2.0f);
  // the spring's pull (its damping part left out), with its limit while one applies
  const double force = snap.mouse.held ? snap.mouse.force : status_.mouse_stiffness * (grab_spring_.target - held).norm();
  char text[160];
  if (snap.mouse.held && snap.mouse.max_force > 0.0) {
    std::snprintf(text, sizeof text, "%.3g N of %.3g N max%s\nanchor %.3g m/s%s", force, snap.mouse.max_force,
                  force >= 0.95 * snap.mouse.max_force ? " (waits)" : "", snap.mouse.max_speed,
                  grab_spring_.hard ? " (Shift: hard)" : "  Shift: hard");
  } else {
    std::snprintf(text, sizeof text, "%.3g N", force);
  }
  list->AddText(ImVec2(pointer.x + 9.0f, pointer.y - 18.0f), colour, text);
  dump_.state("spring_force", force);
}

void GuiApp::dump_grip_state(const Snapshot& snap) {
  // the grip: anchor, pull, its limits (window tests compare them with what they dragged)
  if (snap.mouse.held) {
    char text[160];
    std::snprintf(text, sizeof text, "%.9g %.9g %.6g %.6g %.6g", snap.mouse.anchor.x(), snap.mouse.anchor.y(),
                  snap.mouse.force, snap.mouse.max_force, snap.mouse.max_speed);
    dump_.state("grip", text);
  }
  // the damage: particles with damage above 0.5 (torn loose: dust), and the reference-place box
  // of those above 0.25 (a crack's faces), "COUNT_OVER_HALF PARTICLES COUNT X0 X1 Y0 Y1"
  if (!snap.geometry || snap.damage.size() != snap.geometry->reference_x.size()) return;
  long over_half = 0, cracked = 0;
  float x0 = std::numeric_limits<float>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (size_t i = 0; i < snap.damage.size(); ++i) {
    if (snap.damage[i] > 0.5f) ++over_half;
    if (snap.damage[i] <= 0.25f) continue;
    ++cracked;
    const float x = snap.geometry->reference_x[i], y = snap.geometry->reference_y[i];
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  char text[200];
  if (cracked == 0) x0 = x1 = y0 = y1 = 0.0f;
  std::snprintf(text, sizeof text, "%ld %zu %ld %.6g %.6g %.6g %.6g", over_half, snap.damage.size(), cracked, x0, x1,
                y0, y1);
  dump_.state("damage", text);
}

}  // namespace periflex
