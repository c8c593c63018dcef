#include "output/series_row.h"

#include "scene/scene_def.h"

namespace periflex {

std::vector<std::string> series_columns(const std::vector<std::string>& probe_columns, bool with_damage,
                                        bool with_contact) {
  std::vector<std::string> columns = {"t",          "kinetic",       "potential_gravity", "potential_elastic",
                                      "dissipated", "fracture",      "external_work",     "driver_work",
                                      "energy_balance", "violation_position", "violation_velocity"};
  if (with_damage) {
    for (const char* c : {"broken_bonds", "mean_damage", "max_damage"}) columns.push_back(c);
  }
  if (with_contact) {
    for (const char* c : {"contact_force_total", "contact_count"}) columns.push_back(c);
  }
  columns.insert(columns.end(), probe_columns.begin(), probe_columns.end());
  return columns;
}

void series_values(const Sample& s, bool with_damage, bool with_contact, std::vector<double>& out) {
  const Energies& e = s.energies;
  out = {s.time,       e.kinetic,     e.potential_gravity, e.potential_elastic,
         e.dissipated, e.fracture,    e.external_work,     e.driver_work,
         e.balance,    s.violation_position, s.violation_velocity};
  if (with_damage) {
    out.push_back(static_cast<double>(s.broken_bonds));
    out.push_back(s.mean_damage);
    out.push_back(s.max_damage);
  }
  if (with_contact) {
    out.push_back(s.contact_force_total);
    out.push_back(static_cast<double>(s.contact_count));
  }
  out.insert(out.end(), s.probe_values.begin(), s.probe_values.end());
}

std::vector<std::string> series_columns(const Simulation& sim) {
  return series_columns(sim.probe_columns(), sim.info().particles > 0, !sim.scene().contacts.empty());
}

std::vector<std::string> series_columns(const SceneDef& scene) {
  const auto flexible = [&scene](const std::string& body) {
    for (const FlexBodyDef& f : scene.flex_bodies)
      if (f.name == body) return true;
    return false;
  };
  std::vector<std::string> probes;
  for (bool on_particle : {true, false}) {
    for (const ProbeDef& p : scene.probes)
      if (flexible(p.body) == on_particle) Simulation::append_probe_columns(p.name, on_particle, probes);
  }
  return series_columns(probes, !scene.flex_bodies.empty(), !scene.contacts.empty());
}

void fill_series_row(const Simulation& sim, std::shared_ptr<const std::vector<std::string>>& columns, Snapshot& out) {
  if (!columns) columns = std::make_shared<const std::vector<std::string>>(series_columns(sim));
  out.series_columns = columns;
  series_values(sim.sample(), sim.info().particles > 0, !sim.scene().contacts.empty(), out.series);
}

std::string series_unit(const std::string& column) {
  // probe columns: probe.<name>.<quantity>, the quantity after the last dot
  if (column.rfind("probe.", 0) == 0) {
    const std::string q = column.substr(column.rfind('.') + 1);
    if (q == "x" || q == "y") return "m";
    if (q == "vx" || q == "vy") return "m/s";
    if (q == "angle") return "rad";
    if (q == "omega") return "rad/s";
    return "";
  }
  if (column == "t") return "s";
  for (const char* c : {"kinetic", "potential_gravity", "potential_elastic", "dissipated", "fracture",
                        "external_work", "driver_work", "energy_balance"}) {
    if (column == c) return "J";
  }
  if (column == "violation_position") return "m";
  if (column == "violation_velocity") return "m/s";
  if (column == "broken_bonds" || column == "mean_damage" || column == "max_damage" || column == "contact_count")
    return "-";
  if (column == "contact_force_total") return "N";
  if (column == "steps_per_second") return "1/s";
  return "";
}

}  // namespace periflex
