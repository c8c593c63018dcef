#include "app/widget_dump.h"

#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace periflex {

WidgetDump::WidgetDump() {
  const char* path = std::getenv("PERIFLEX_GUI_WIDGETS");
  if (path) path_ = path;
}

void WidgetDump::begin_frame() {
  if (enabled()) lines_.clear();
}

void WidgetDump::note_item(const std::string& name) {
  if (!enabled() || !ImGui::IsItemVisible()) return;
  // ImGui's coordinates are the window's (before the framebuffer scale)
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  char text[160];
  std::snprintf(text, sizeof text, "%.0f %.0f %.0f %.0f", a.x, a.y, b.x, b.y);
  lines_["widget " + name] = text;
}

void WidgetDump::state(const std::string& key, const std::string& value) {
  if (enabled()) lines_["state " + key] = value;
}

void WidgetDump::state(const std::string& key, double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  state(key, std::string(text));
}

void WidgetDump::end_frame() {
  if (!enabled()) return;
  std::string text;
  for (const auto& [key, value] : lines_) text += key + " " + value + "\n";
  if (text == written_) return;
  const std::string temporary = path_ + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << text;
    if (!out) return;
  }
  if (std::rename(temporary.c_str(), path_.c_str()) == 0) written_ = text;
}

}  // namespace periflex
