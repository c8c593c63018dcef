// The knife: in knife mode (K, or the Simulation panel's toggle) a left-drag over the picture
// draws a segment, and its release asks the simulation thread to cut the bonds the segment
// crosses, as a notch of the scene would, whether the run is paused or running. The particles
// are tested where they are drawn, so under a magnified deformation the bonds cut are those the
// eye sees crossed. Reset brings the bonds back.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app/gui_app.h"

namespace periflex {

namespace {

// a drag shorter than this (pixels) is a click, not a cut
constexpr double kShortestCutPixels = 3.0;

}  // namespace

void GuiApp::knife_input(const Vec2& world) {
  knife_to_ = world;
  if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) return;
  // released: a cut, unless the drag was a click
  cutting_ = false;
  const double window_height = std::max(1.0f, ImGui::GetIO().DisplaySize.y);
  const double pixels = (knife_to_ - knife_from_).norm() / std::max(1e-300, camera_.view_height) * window_height;
  if (pixels < kShortestCutPixels) return;
  SimCommand c{command::Cut{knife_from_, knife_to_, renderer_->drawn_x(), renderer_->drawn_y()}, "mouse"};
  char text[160];
  std::snprintf(text, sizeof text, "knife from (%.6g, %.6g) to (%.6g, %.6g) m", knife_from_.x(), knife_from_.y(),
                knife_to_.x(), knife_to_.y());
  log_.add(text);
  send(std::move(c));
}

void GuiApp::draw_knife(int fb_width, int fb_height) {
  if (!cutting_) return;
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x > 0.0f ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  const auto window_point = [&](const Vec2& world) {
    const Vec2 p = camera_.to_pixels(world, fb_width, fb_height);
    return ImVec2(static_cast<float>(p.x()) / scale, static_cast<float>(p.y()) / scale);
  };
  const ImVec2 a = window_point(knife_from_), b = window_point(knife_to_);
  ImDrawList* list = ImGui::GetForegroundDrawList();
  const ImU32 colour = IM_COL32(255, 70, 60, 255);
  list->AddLine(a, b, colour, 2.0f);
  list->AddCircleFilled(a, 3.0f, colour);
  list->AddCircleFilled(b, 3.0f, colour);
  list->AddText(ImVec2(b.x + 8.0f, b.y - 16.0f), colour, "cut");
}

}  // namespace periflex
