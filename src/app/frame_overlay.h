// The overlay (scene name, time, colour legend) on frames drawn outside the window's own frame,
// such as the frames recorded from the window: the same Renderer::draw_overlay the window and its
// screenshots use, through a Dear ImGui context of its own so the window's panels never appear.
// Needs the window's OpenGL context current; internal to src/app/.
#pragma once

#include "render/renderer.h"
#include "solve/snapshot.h"

struct ImGuiContext;

namespace periflex {

class FrameOverlay {
 public:
  // Creates the ImGui context and its OpenGL 3 back end under the current GL context.
  // Throws std::runtime_error when the back end cannot start.
  FrameOverlay();
  ~FrameOverlay();
  FrameOverlay(const FrameOverlay&) = delete;
  FrameOverlay& operator=(const FrameOverlay&) = delete;

  // Draws the overlay of `snapshot` over what the bound framebuffer holds (width x height
  // pixels), after renderer.draw of that snapshot (the legend shows the range it used).
  // Leaves the ImGui context that was current before current again.
  void draw(Renderer& renderer, const Snapshot& snapshot, const RenderSettings& settings, int width,
            int height);

 private:
  ImGuiContext* context_ = nullptr;
};

}  // namespace periflex
