#include "app/frame_overlay.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <mutex>
#include <stdexcept>

namespace periflex {

FrameOverlay::FrameOverlay() {
  // ImGui's current context is process-wide: create ours under the shared lock, then restore
  ImGuiContextLock lock;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  // no input, no settings or log files
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::GetIO().LogFilename = nullptr;
  const bool ok = ImGui_ImplOpenGL3_Init("#version 330");
  if (!ok) {
    ImGui::DestroyContext(context_);
    context_ = nullptr;
  }
  ImGui::SetCurrentContext(previous);
  if (!ok) throw std::runtime_error("Dear ImGui's OpenGL 3 back end could not start for the overlay");
}

FrameOverlay::~FrameOverlay() {
  if (!context_) return;
  ImGuiContextLock lock;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(context_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
  ImGui::SetCurrentContext(previous == context_ ? nullptr : previous);
}

void FrameOverlay::draw(Renderer& renderer, const Snapshot& snapshot, const RenderSettings& settings,
                        int width, int height) {
  if (!settings.show_overlay) return;
  ImGuiContextLock lock;
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(context_);
  // one frame of our own context, sized to the target in pixels
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  try {
    renderer.draw_overlay(snapshot, settings, width, height);
  } catch (...) {
    // close the frame, so the next one can start, and give the window its context back
    ImGui::EndFrame();
    ImGui::SetCurrentContext(previous);
    throw;
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  ImGui::SetCurrentContext(previous);
}

}  // namespace periflex
