// The panel column: simulation, live parameters, view, plots, export and log. Panels show only
// what the scene has (no damage or fracture controls without particles).
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "app/gui_app.h"
#include "app/view_fit.h"
#include "output/series_row.h"
#include "io/frame_writer.h"

namespace periflex {

namespace {

// real-time factors offered; 0 runs as fast as possible
constexpr double kSpeeds[] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 0.0};
constexpr int kSpeedCount = sizeof(kSpeeds) / sizeof(kSpeeds[0]);

std::string speed_label(double speed) {
  if (speed <= 0.0) return "as fast as possible";
  char text[32];
  std::snprintf(text, sizeof text, "%gx", speed);
  return text;
}

// a red line of text
void error_text(const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

void warning_text(const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

// a number typed and confirmed with Enter (no half-typed values reach the solver)
bool input_number(const char* label, double& value, const char* format = "%.6g") {
  return ImGui::InputDouble(label, &value, 0.0, 0.0, format, ImGuiInputTextFlags_EnterReturnsTrue);
}

bool has_particles(const Snapshot& s) { return s.geometry && s.geometry->has_particles(); }

}  // namespace

void GuiApp::draw_panels(int fb_width, int fb_height) {
  ImGuiIO& io = ImGui::GetIO();
  const float scale = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth / scale, fb_height / scale));
  ImGui::Begin("periflex", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::PushItemWidth(150.0f);
  panel_simulation();
  const bool about_open = ImGui::CollapsingHeader("About this scene");
  dump_.note_item("description_header");
  if (about_open) panel_description();
  const bool history_open = ImGui::CollapsingHeader("History", ImGuiTreeNodeFlags_DefaultOpen);
  dump_.note_item("history_header");
  if (history_open) panel_history();
  if (ImGui::CollapsingHeader("Live parameters", ImGuiTreeNodeFlags_DefaultOpen)) panel_parameters();
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) panel_view();
  if (ImGui::CollapsingHeader("Plots")) panel_plots();
  const bool export_open = ImGui::CollapsingHeader("Export");
  dump_.note_item("export_header");
  if (export_open) panel_export();
  if (ImGui::CollapsingHeader("Log", ImGuiTreeNodeFlags_DefaultOpen)) panel_log();
  ImGui::PopItemWidth();
  ImGui::End();
  numerical_error_modal();
  unstable_step_modal();
}

void GuiApp::panel_simulation() {
  ImGui::Text("%s", status_.scene_name.c_str());
  ImGui::Text("t = %.6g s of %.6g   step %ld", status_.time, status_.end_time, status_.step);
  if (ImGui::Button(status_.running ? "Pause" : "Run", ImVec2(60, 0))) {
    send(SimCommand{command::ToggleRun{}});
  }
  dump_.note_item("run_pause");
  ImGui::SameLine();
  if (ImGui::Button("Step")) send(SimCommand{command::Step{}});
  dump_.note_item("step");
  ImGui::SameLine();
  if (ImGui::Button("Reset")) send(SimCommand{command::Reset{}});
  dump_.note_item("reset");
  ImGui::SameLine();
  if (ImGui::Button("Reload")) send(SimCommand{command::Reload{}});
  // the knife: a left-drag over the picture cuts the bonds it crosses (undone by Reset)
  if (has_particles(worker_.snapshot())) {
    ImGui::SameLine();
    if (ImGui::Checkbox("knife (K)", &knife_)) {
      cutting_ = false;
      log_.add(knife_ ? "knife on (ui)" : "knife off (ui)");
    }
    dump_.note_item("knife");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag across a flexible body to cut its bonds; Reset undoes");
  }

  // several steps at once, or up to a time: a single step of a fracture scene is 0.4 us
  ImGui::PushItemWidth(110.0f);
  ImGui::InputInt("##stepcount", &step_count_, 0, 0);
  dump_.note_item("step_count");
  step_count_ = std::clamp(step_count_, 1, 100000000);
  ImGui::SameLine();
  if (ImGui::Button("Step N")) {
    send(SimCommand{command::Step{step_count_}});
  }
  dump_.note_item("step_n");
  if (step_to_time_ <= 0.0 && status_.end_time > 0.0) step_to_time_ = status_.end_time / 10.0;
  ImGui::InputDouble("##steptime", &step_to_time_, 0.0, 0.0, "%.6g");
  dump_.note_item("step_to_time");
  ImGui::SameLine();
  if (ImGui::Button("Step to t")) {
    send(SimCommand{command::StepTo{step_to_time_}});
  }
  dump_.note_item("step_to");
  ImGui::PopItemWidth();

  // pace: the nearest offered factor is shown as chosen
  int current = 0;
  for (int i = 0; i < kSpeedCount; ++i) {
    const bool max_now = status_.speed <= 0.0, max_i = kSpeeds[i] <= 0.0;
    if (max_now && max_i) current = i;
    const auto distance = [&](int k) { return std::fabs(std::log(kSpeeds[k] / status_.speed)); };
    if (!max_now && !max_i && (kSpeeds[current] <= 0.0 || distance(i) < distance(current))) {
      current = i;
    }
  }
  if (ImGui::BeginCombo("speed", speed_label(status_.speed).c_str())) {
    for (int i = 0; i < kSpeedCount; ++i) {
      if (ImGui::Selectable(speed_label(kSpeeds[i]).c_str(), i == current)) {
        send(SimCommand{command::SetSpeed{kSpeeds[i]}});
      }
    }
    ImGui::EndCombo();
  }
  ImGui::Text("%.0f steps/s, %.3g sim s per wall s", status_.steps_per_second,
              status_.sim_seconds_per_second);

  // scenes shipped in scenes/
  if (!scenes_.empty()) {
    const char* preview = scene_choice_ >= 0 ? scenes_[scene_choice_].c_str() : "(other file)";
    if (ImGui::BeginCombo("##scene", preview)) {
      for (int i = 0; i < static_cast<int>(scenes_.size()); ++i) {
        if (ImGui::Selectable(scenes_[i].c_str(), i == scene_choice_)) scene_choice_ = i;
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Open") && scene_choice_ >= 0) {
      send(SimCommand{command::LoadScene{resolve_scene_path(scenes_[scene_choice_])}});
    }
  }
  if (!status_.load_error.empty()) error_text("Load failed (old scene kept): " + status_.load_error);
  if (status_.numerical_error) error_text("Stopped: " + status_.numerical_message);
}

void GuiApp::panel_parameters() {
  // the panel edits a copy of the solver's settings; every confirmed change is sent whole
  LiveSettings edit = status_.settings;
  bool changed = false;
  const bool particles = has_particles(worker_.snapshot());

  const std::vector<std::string> integrators = integrator_names();
  if (ImGui::BeginCombo("integrator", edit.integrator.c_str())) {
    for (const std::string& name : integrators) {
      if (ImGui::Selectable(name.c_str(), name == edit.integrator)) {
        edit.integrator = name;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  if (status_.rejected_key == "integrator") error_text("refused: " + status_.rejected_message);
  const double dt_before = edit.dt;
  const bool dt_typed = input_number("dt [s]", edit.dt) && edit.dt != dt_before;
  changed |= dt_typed;
  dump_.note_item("dt");
  // a new step is held to the stability limit again: one past it runs only once confirmed
  if (dt_typed) edit.allow_unstable = false;
  // a refused value is shown where it was typed, not only in the log
  const auto refusal = [this](const char* key) {
    if (status_.rejected_key != key) return;
    error_text("refused: " + status_.rejected_message);
    dump_.note_item(std::string(key) + "_refusal");
  };
  refusal("dt");
  const double critical = status_.info.critical_time_step;
  if (critical > 0.0) {
    ImGui::Text("critical dt %.4g s", critical);
    if (edit.dt > critical) warning_text("dt exceeds the critical step: explicit peridynamics will diverge");
  }

  static const char* methods[] = {"none", "baumgarte", "projection"};
  int method = static_cast<int>(edit.correction.method);
  if (ImGui::Combo("correction", &method, methods, 3)) {
    edit.correction.method = static_cast<CorrectionDef::Method>(method);
    changed = true;
  }
  if (edit.correction.method == CorrectionDef::Method::kBaumgarte) {
    changed |= input_number("alpha", edit.correction.alpha);
    changed |= input_number("beta", edit.correction.beta);
  } else if (edit.correction.method == CorrectionDef::Method::kProjection) {
    changed |= input_number("tolerance", edit.correction.tolerance, "%.3g");
  }

  if (particles) {
    changed |= input_number("bond damping [Pa s]", edit.bond_damping);
    dump_.note_item("bond_damping");
    refusal("bond_damping");
    changed |= input_number("global damping [1/s]", edit.global_damping);
    refusal("global_damping");
    changed |= ImGui::Checkbox("fracture", &edit.fracture);
  }
  // a refusal that names no field of this panel
  static const char* fields[] = {"dt", "integrator", "bond_damping", "global_damping"};
  const bool placed = std::find(std::begin(fields), std::end(fields), status_.rejected_key) != std::end(fields) &&
                      (particles || status_.rejected_key == "dt" || status_.rejected_key == "integrator");
  if (!status_.rejected_message.empty() && !placed) error_text("refused: " + status_.rejected_message);
  if (changed) {
    send(SimCommand{command::ApplySettings{edit}});
    // a refusal of this step for the stability limit is answered with the offer to run it anyway
    if (dt_typed && critical > 0.0) unstable_offer_ = UnstableOffer{edit, sent_};
  }
  for (const std::string& w : status_.info.warnings) warning_text(w);
}

namespace {

// Describes what differs between two view settings, for the log ("" when nothing does).
std::string describe_view_change(const RenderSettings& a, const RenderSettings& b) {
  std::string out;
  const auto flag = [&out](const char* name, bool before, bool after) {
    if (before != after) out += std::string(" ") + name + (after ? " on" : " off");
  };
  if (a.field != b.field) out += std::string(" field ") + field_name(b.field);
  if (a.colormap != b.colormap) out += " colour map " + b.colormap;
  if (a.deform != b.deform) {
    char text[48];
    std::snprintf(text, sizeof text, " deformation x%g", double(b.deform));
    out += b.deform < 0.0f ? std::string(" deformation auto") : std::string(text);
  }
  if (a.auto_range != b.auto_range) out += b.auto_range ? " range auto" : " range fixed";
  if (!b.auto_range && (a.range_min != b.range_min || a.range_max != b.range_max)) {
    out += " range " + std::to_string(b.range_min) + " .. " + std::to_string(b.range_max);
  }
  flag("bodies", a.show_bodies, b.show_bodies);
  flag("markers", a.show_markers, b.show_markers);
  flag("springs", a.show_springs, b.show_springs);
  flag("bonds", a.show_bonds, b.show_bonds);
  flag("probes", a.show_probes, b.show_probes);
  flag("trails", a.show_trails, b.show_trails);
  flag("contacts", a.show_contacts, b.show_contacts);
  flag("overlay", a.show_overlay, b.show_overlay);
  return out;
}

}  // namespace

void GuiApp::panel_view() {
  // every change made here is logged once the panel is drawn
  const RenderSettings before = render_;
  const int follow_before = follow_;
  panel_view_controls();
  const std::string change = describe_view_change(before, render_);
  if (!change.empty()) log_.add("view:" + change + " (ui)");
  if (follow_ != follow_before) {
    const Snapshot& snap = worker_.snapshot();
    log_.add(follow_ > 0 && snap.geometry ? "follow " + snap.geometry->bodies[follow_].name + " (ui)"
                                          : std::string("follow none (ui)"));
  }
}

void GuiApp::panel_view_controls() {
  const Snapshot& snap = worker_.snapshot();
  const bool particles = has_particles(snap);
  if (particles) {
    static const char* fields[] = {"damage", "displacement", "speed", "strain"};
    int field = static_cast<int>(render_.field);
    if (ImGui::Combo("colour field", &field, fields, 4)) render_.field = static_cast<ColorField>(field);
    ImGui::Checkbox("auto range", &render_.auto_range);
    if (!render_.auto_range) {
      ImGui::InputFloat("min", &render_.range_min, 0.0f, 0.0f, "%.4g");
      ImGui::InputFloat("max", &render_.range_max, 0.0f, 0.0f, "%.4g");
    } else {
      ImGui::Text("range %.4g .. %.4g", renderer_->last_range_min(), renderer_->last_range_max());
    }
    if (ImGui::BeginCombo("colour map", render_.colormap.c_str())) {
      for (const std::string& name : renderer_->colormap_names()) {
        if (ImGui::Selectable(name.c_str(), name == render_.colormap)) render_.colormap = name;
      }
      ImGui::EndCombo();
    }
    ImGui::SliderFloat("particle size", &render_.particle_scale, 0.2f, 2.0f, "%.2f");
    panel_deformation();
    ImGui::Checkbox("bonds", &render_.show_bonds);
    ImGui::SameLine();
  }
  ImGui::Checkbox("bodies", &render_.show_bodies);
  ImGui::SameLine();
  ImGui::Checkbox("markers", &render_.show_markers);
  ImGui::Checkbox("springs", &render_.show_springs);
  ImGui::SameLine();
  ImGui::Checkbox("probes", &render_.show_probes);
  ImGui::SameLine();
  ImGui::Checkbox("trails", &render_.show_trails);
  ImGui::Checkbox("contacts (C)", &render_.show_contacts);
  dump_.note_item("show_contacts");
  ImGui::SameLine();
  ImGui::Checkbox("overlay", &render_.show_overlay);

  // follow one rigid body, or none
  if (snap.geometry && snap.geometry->bodies.size() > 1) {
    const auto& bodies = snap.geometry->bodies;
    const bool following = follow_ > 0 && follow_ < static_cast<int>(bodies.size());
    const char* preview = following ? bodies[follow_].name.c_str() : "(none)";
    if (ImGui::BeginCombo("follow", preview)) {
      if (ImGui::Selectable("(none)", follow_ <= 0)) follow_ = -1;
      for (int b = 1; b < static_cast<int>(bodies.size()); ++b) {
        if (ImGui::Selectable(bodies[b].name.c_str(), b == follow_)) follow_ = b;
      }
      ImGui::EndCombo();
    }
  }
  if (ImGui::Button("Fit view (F)")) {
    fit_pending_ = true;
    follow_ = -1;
  }
}

void GuiApp::panel_deformation() {
  // the magnification of the flexible bodies' deformation: automatic, or a factor on a
  // logarithmic slider (0: undeformed; Ctrl+click types a value)
  bool automatic = render_.deform < 0.0f;
  if (ImGui::Checkbox("##deform_auto", &automatic)) {
    render_.deform = automatic ? kAutoDeform : static_cast<float>(renderer_->last_deform());
  }
  dump_.note_item("deform_auto");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("automatic magnification");
  ImGui::SameLine();
  float factor = automatic ? static_cast<float>(renderer_->last_deform()) : render_.deform;
  if (ImGui::SliderFloat("deformation", &factor, 0.0f, static_cast<float>(kMaxDeformSlider),
                         automatic ? "x%g (auto)" : "x%g", ImGuiSliderFlags_Logarithmic)) {
    render_.deform = std::clamp(factor, 0.0f, static_cast<float>(kMaxDeformSlider));
  }
  dump_.note_item("deform");
}

void GuiApp::panel_plots() {
  // the plot window, and a line per main quantity for a glance
  ImGui::Checkbox("plot window (P)", &show_plot_);
  dump_.note_item("plot_toggle");
  const bool particles = has_particles(worker_.snapshot());
  const bool constrained = status_.info.constraint_equations > 0;
  ImGui::Text("t = %.4g .. %.4g s, %zu points", history_.first_time(), history_.last_time(), history_.size());
  static const char* glance[] = {"kinetic", "potential_gravity", "potential_elastic", "energy_balance",
                                 "violation_position", "broken_bonds", "max_damage", "steps_per_second"};
  for (const char* name : glance) {
    const std::string column = name;
    if (!particles && (column == "broken_bonds" || column == "max_damage")) continue;
    if (!constrained && column == "violation_position") continue;
    const int k = history_.index_of(column);
    if (k < 0) continue;
    const std::vector<double>& v = history_.values(k);
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%.4g", v.empty() ? 0.0 : v.back());
    const std::string unit = series_unit(column);
    ImGui::Text("%s%s", name, unit.empty() ? "" : (" [" + unit + "]").c_str());
    const auto value = [](void* data, int i) { return static_cast<float>((*static_cast<const std::vector<double>*>(data))[i]); };
    ImGui::PlotLines(("##plot" + column).c_str(), value, const_cast<std::vector<double>*>(&v), static_cast<int>(v.size()),
                     0, overlay, FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 40.0f));
  }
}

void GuiApp::panel_export() {
  ImGui::InputText("##shot", screenshot_path_, sizeof screenshot_path_);
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (S)")) {
    pending_screenshot_ = screenshot_path_[0] ? std::string(screenshot_path_) : default_screenshot_name();
  }

  ImGui::Separator();
  ImGui::TextWrapped("Record: a folder for a PNG sequence, or a movie file: .mp4, .webm, .mkv, .gif or .avi (needs ffmpeg)");
  ImGui::InputText("##record", record_path_, sizeof record_path_);
  dump_.note_item("record_path");
  if (record_interval_ <= 0.0) record_interval_ = status_.end_time > 0.0 ? status_.end_time / 200.0 : 0.01;
  input_number("every [sim s]", record_interval_);
  dump_.note_item("record_interval");
  ImGui::InputFloat("movie fps", &record_fps_, 0.0f, 0.0f, "%.0f");
  if (!writer_) {
    // a request: recording starts between frames, outside this ImGui frame
    if (ImGui::Button("Start recording")) {
      pending_record_start_ = RecordRequest{record_path_, record_interval_, record_fps_, "ui"};
    }
    dump_.note_item("start_recording");
  } else {
    ImGui::Text("%ld frames written", writer_->frames_written());
    if (ImGui::Button("Stop recording")) pending_record_stop_ = true;
    dump_.note_item("stop_recording");
  }
  if (!record_message_.empty()) ImGui::TextWrapped("%s", record_message_.c_str());
}

void GuiApp::panel_log() {
  ImGui::BeginChild("log", ImVec2(0, 160), true, ImGuiWindowFlags_HorizontalScrollbar);
  for (const std::string& line : log_.lines()) ImGui::TextUnformatted(line.c_str());
  // follow new lines
  const long total = log_.total();
  if (total != log_shown_) {
    ImGui::SetScrollHereY(1.0f);
    log_shown_ = total;
  }
  ImGui::EndChild();
}

void GuiApp::unstable_step_modal() {
  // once the worker has answered: a step refused for the stability limit is offered to run anyway
  constexpr const char* kTitle = "Run past the stable step?";
  if (unstable_offer_ && status_.commands_applied >= unstable_offer_->sent) {
    if (status_.rejected_key == "dt" && status_.rejected_message.find("critical step") != std::string::npos) {
      unstable_asked_ = unstable_offer_->settings;
      ImGui::OpenPopup(kTitle);
    }
    unstable_offer_.reset();
  }
  if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::PushTextWrapPos(520.0f);
  ImGui::TextWrapped("dt = %.6g s is above the stable step of the explicit integrator (critical step %.4g s).",
                     unstable_asked_.dt, status_.info.critical_time_step);
  ImGui::TextWrapped("Run it anyway to watch the integration diverge: the energy grows step by step until the "
                     "divergence check stops the run with a numerical-failure diagnostic.");
  ImGui::PopTextWrapPos();
  if (ImGui::Button("Run past the limit")) {
    LiveSettings past_the_limit = unstable_asked_;
    past_the_limit.allow_unstable = true;
    send(SimCommand{command::ApplySettings{past_the_limit}});
    ImGui::CloseCurrentPopup();
  }
  dump_.note_item("unstable_confirm");
  ImGui::SameLine();
  if (ImGui::Button("Keep the stable step")) ImGui::CloseCurrentPopup();
  dump_.note_item("unstable_cancel");
  ImGui::EndPopup();
}

void GuiApp::numerical_error_modal() {
  // open once per failure; the run stays paused until reset, reload or a settings change
  if (status_.numerical_error && status_.numerical_error->step != shown_error_step_) {
    shown_error_step_ = status_.numerical_error->step;
    ImGui::OpenPopup("Numerical failure");
  }
  if (ImGui::BeginPopupModal("Numerical failure", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (status_.numerical_error) {
      const NumericalDiagnostic& d = *status_.numerical_error;
      ImGui::Text("quantity: %s", d.quantity.c_str());
      ImGui::Text("step %ld, t = %.9g s", d.step, d.time);
      ImGui::PushTextWrapPos(520.0f);
      ImGui::TextWrapped("likely cause: %s", d.cause.c_str());
      ImGui::TextWrapped("remedy: %s", d.remedy.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::TextUnformatted("The simulation is paused.");
    if (ImGui::Button("Reset")) {
      send(SimCommand{command::Reset{}});
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Close")) ImGui::CloseCurrentPopup();
    dump_.note_item("failure_close");
    ImGui::EndPopup();
  }
}

}  // namespace periflex
