// The History panel: the timeline of the states the simulation thread keeps (scrubbed with the
// slider, or Left / Right), "Resume from here", and the cadence and memory budget of the ring.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app/gui_app.h"

namespace periflex {

void GuiApp::panel_history() {
  const WorkerStatus& s = status_;
  // the timeline spans the states kept and the live instant; the handle sits at the time shown
  const double lo = s.history_states ? s.history_first : s.time;
  const double hi = std::max(s.history_states ? s.history_last : s.time, s.time);
  double shown = s.time;
  ImGui::PushItemWidth(-1.0f);
  ImGui::BeginDisabled(s.history_states == 0 || hi <= lo);
  if (ImGui::SliderScalar("##timeline", ImGuiDataType_Double, &shown, &lo, &hi, "t = %.6g s")) {
    send(SimCommand{command::Scrub{shown}});
  }
  ImGui::EndDisabled();
  dump_.note_item("history_slider");
  ImGui::PopItemWidth();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag to go back and forth (paused); Left / Right arrows step");

  // resuming drops the states after the one shown: its future is computed again
  ImGui::BeginDisabled(s.scrub < 0);
  if (ImGui::Button("Resume from here")) send(SimCommand{command::Resume{}});
  ImGui::EndDisabled();
  dump_.note_item("history_resume");
  ImGui::SameLine();
  if (s.scrub >= 0) ImGui::Text("state %ld of %zu", s.scrub + 1, s.history_states);
  else ImGui::Text("%zu states", s.history_states);

  // memory: used of the budget, and whether the states are kept compressed
  const double used = static_cast<double>(s.history_bytes) / (1 << 20);
  const double total = static_cast<double>(s.history_budget) / (1 << 20);
  char text[64];
  std::snprintf(text, sizeof text, "%.1f / %.0f MB%s", used, total, s.history_compressed ? " (compressed)" : "");
  ImGui::ProgressBar(total > 0.0 ? static_cast<float>(used / total) : 0.0f, ImVec2(-1.0f, 0.0f), text);
  dump_.note_item("history_memory");
  if (s.history_too_large) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    ImGui::TextWrapped("one state is larger than the whole budget: none kept");
    ImGui::PopStyleColor();
  }

  // the cadence in simulated seconds (0: off, no cost) and the budget, applied with Enter
  if (history_edit_generation_ != s.generation || !history_edited_) {
    history_interval_ = s.history_interval;
    history_budget_mb_ = static_cast<int>(s.history_budget >> 20);
  }
  history_edit_generation_ = s.generation;
  bool changed = ImGui::InputDouble("every [s]", &history_interval_, 0.0, 0.0, "%.6g",
                                    ImGuiInputTextFlags_EnterReturnsTrue);
  dump_.note_item("history_interval");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("simulated seconds between saved states; 0 keeps none");
  history_edited_ = ImGui::IsItemActive();
  changed |= ImGui::InputInt("budget [MB]", &history_budget_mb_, 0, 0, ImGuiInputTextFlags_EnterReturnsTrue);
  dump_.note_item("history_budget");
  history_edited_ = history_edited_ || ImGui::IsItemActive();
  if (changed) {
    send(SimCommand{command::History{std::max(0.0, history_interval_), std::clamp(history_budget_mb_, 1, 1 << 20)}});
  }
}

}  // namespace periflex
