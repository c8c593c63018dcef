// The rigid body last clicked, inspected: its coordinates q = (x, y, phi) and velocities, and
// the reactions of the joints and drivers that hold it, the Lagrange multipliers as a force and
// a moment about the body's reference point (Snapshot::reactions), with the force's magnitude.
#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "app/gui_app.h"

namespace periflex {

void GuiApp::inspect_body(int fb_width) {
  const Snapshot& snap = worker_.snapshot();
  // the simulation thread adds the reactions to its snapshots only while they are shown
  const bool wanted = inspected_body_ > 0;
  if (wanted != reactions_asked_) {
    send(SimCommand{command::Reactions{wanted}});
    reactions_asked_ = wanted;
  }
  if (inspected_body_ <= 0 || !snap.geometry || inspected_body_ >= static_cast<int>(snap.bodies.size()) ||
      inspected_body_ >= static_cast<int>(snap.geometry->bodies.size())) {
    return;
  }
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x > 0.0f ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  // at the picture's top right, clear of the overlay at its left
  ImGui::SetNextWindowPos(ImVec2(fb_width / scale - 12.0f, 40.0f), ImGuiCond_Appearing, ImVec2(1.0f, 0.0f));
  bool open = true;
  const std::string& name = snap.geometry->bodies[inspected_body_].name;
  if (!ImGui::Begin("Rigid body", &open, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  const Snapshot::Pose& p = snap.bodies[inspected_body_];
  ImGui::Text("%s%s", name.c_str(), snap.geometry->bodies[inspected_body_].is_virtual ? " (virtual)" : "");
  dump_.note_item("body_inspector");
  ImGui::Separator();
  ImGui::Text("q   x %.6g m, y %.6g m, phi %.6g rad", p.x, p.y, p.angle);
  ImGui::Text("qd  vx %.4g m/s, vy %.4g m/s, omega %.4g rad/s", p.vx, p.vy, p.omega);
  char text[200];
  std::snprintf(text, sizeof text, "%s %.9g %.9g %.9g %.9g %.9g %.9g", name.c_str(), p.x, p.y, p.angle, p.vx, p.vy,
                p.omega);
  dump_.state("body_inspected", text);
  // what holds it
  bool any = false;
  for (const Snapshot::Reaction& r : snap.reactions) {
    if (r.body != inspected_body_) continue;
    if (!any) {
      ImGui::Separator();
      ImGui::TextUnformatted("reactions on the body (force; moment about its reference point)");
      any = true;
    }
    ImGui::Text("%-14s F (%.4g, %.4g) N, |F| %.4g N, M %.4g N m", r.joint.c_str(), r.fx, r.fy,
                std::hypot(r.fx, r.fy), r.moment);
    std::snprintf(text, sizeof text, "%.9g %.9g %.9g", r.fx, r.fy, r.moment);
    dump_.state("reaction_" + r.joint, text);
  }
  if (!any) ImGui::TextDisabled("no joint holds it");
  ImGui::End();
  if (!open) inspected_body_ = -1;
}

}  // namespace periflex
