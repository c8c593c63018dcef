// What the window shows to teach with: the F1 list of keys and mouse actions, the scene's
// description, the frame rate and the solver's pace, and the scene file reloaded when it
// changes on disk (with its error shown over the picture when the new file is bad).
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "app/gui_app.h"
#include "app/key_help.h"
#include "app/view_fit.h"

namespace periflex {

namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void GuiApp::help_window(int fb_width, int fb_height) {
  if (!show_help_) return;
  // centred over the picture the first time; it can be moved and closed like any window
  const float scale = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
  ImGui::SetNextWindowPos(ImVec2((kPanelWidth + 0.5f * (fb_width - kPanelWidth)) / scale, 0.5f * fb_height / scale),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::Begin("Keys and mouse (F1 to close)", &show_help_,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
      for (const KeyHelp& k : kKeyHelp) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(k.input);
        ImGui::TableSetColumnIndex(1);
        ImGui::TextUnformatted(k.action);
      }
      ImGui::EndTable();
    }
    dump_.note_item("help_table");
  }
  ImGui::End();
}

void GuiApp::panel_description() {
  // the scene file's opening comment (or its scene.description), wrapped to the panel
  if (description_.empty()) {
    ImGui::TextDisabled("(the scene file has no leading comment or scene.description)");
  } else {
    ImGui::TextWrapped("%s", description_.c_str());
  }
  dump_.note_item("description");
  // what the scene holds: its particles, and where each flexible body's geometry came from
  if (status_.info.particles > 0) ImGui::Text("%ld particles", static_cast<long>(status_.info.particles));
  std::string geometry;
  for (const std::string& line : status_.geometry_summary) {
    ImGui::TextWrapped("%s", line.c_str());
    geometry += (geometry.empty() ? "" : " | ") + line;
  }
  dump_.state("particles", std::to_string(status_.info.particles));
  dump_.state("geometry", geometry);
}

void GuiApp::draw_performance(int fb_width) {
  // frame time smoothed over about half a second of frames
  const double now = steady_seconds();
  if (last_frame_wall_ > 0.0) {
    const double dt = now - last_frame_wall_;
    const double weight = std::min(1.0, dt / 0.5);
    frame_seconds_ = frame_seconds_ > 0.0 ? frame_seconds_ + weight * (dt - frame_seconds_) : dt;
  }
  last_frame_wall_ = now;

  // top right of the picture, always: window and solver pace
  char text[200];
  const double fps = frame_seconds_ > 0.0 ? 1.0 / frame_seconds_ : 0.0;
  if (status_.running) {
    std::snprintf(text, sizeof text, "%.0f fps (%.1f ms)   %.4g steps/s   %.3g x real time", fps,
                  1e3 * frame_seconds_, status_.steps_per_second, status_.sim_seconds_per_second);
  } else {
    std::snprintf(text, sizeof text, "%.0f fps (%.1f ms)   paused", fps, 1e3 * frame_seconds_);
  }
  const float scale = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
  const ImVec2 size = ImGui::CalcTextSize(text);
  const float x = fb_width / scale - size.x - 12.0f, y = 8.0f;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled(ImVec2(x - 4, y - 2), ImVec2(x + size.x + 4, y + size.y + 2), IM_COL32(0, 0, 0, 140), 3.0f);
  dl->AddText(ImVec2(x, y), IM_COL32(240, 240, 240, 255), text);
  dump_.state("fps", fps);
  dump_.state("performance", text);
}

void GuiApp::watch_scene_file() {
  // saved again: reload through the worker's loader, which checks the scene and its limits
  if (scene_watch_.changed(steady_seconds())) {
    log_.add("scene file " + scene_watch_.path() + " changed on disk: reloading");
    send(SimCommand{command::Reload{}, "file"});
    return;
  }
  // a point file, image or drawing the scene reads, saved again: the same reload
  for (FileWatch& watch : geometry_watches_) {
    if (!watch.changed(steady_seconds())) continue;
    log_.add("geometry file " + watch.path() + " changed on disk: reloading");
    send(SimCommand{command::Reload{}, "file"});
    return;
  }
}

void GuiApp::draw_load_error(int fb_width) {
  // a bad scene file: its error over the picture, where the eye is, until a good load
  if (status_.load_error.empty()) return;
  const float scale = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
  const float left = kPanelWidth / scale + 12.0f, width = fb_width / scale - left - 12.0f;
  ImGui::SetNextWindowPos(ImVec2(left, 40.0f));
  ImGui::SetNextWindowSize(ImVec2(std::max(200.0f, width), 0.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::PushStyleColor(ImGuiCol_Border, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
  ImGui::Begin("##load_error", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.55f, 0.5f, 1.0f));
  ImGui::TextWrapped("The scene file could not be loaded; the scene before it keeps running.\n%s",
                     status_.load_error.c_str());
  ImGui::PopStyleColor();
  dump_.note_item("load_error");
  ImGui::End();
  ImGui::PopStyleColor();
}

}  // namespace periflex
