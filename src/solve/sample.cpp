// The sample of a run at the current state: energies, constraint violations, damage, contact
// totals and the probes' columns (one row of series.csv).
#include "solve/simulation_impl.h"

#include <algorithm>
#include <string>
#include <vector>

namespace periflex {

void Simulation::append_probe_columns(const std::string& name, bool on_particle, std::vector<std::string>& out) {
  for (const char* c : {"x", "y", "vx", "vy"}) out.push_back("probe." + name + "." + c);
  if (!on_particle) {
    out.push_back("probe." + name + ".angle");
    out.push_back("probe." + name + ".omega");
  }
}

std::vector<std::string> Simulation::probe_columns() const {
  std::vector<std::string> columns;
  for (const auto& p : impl_->model->probes) append_probe_columns(p.name, p.is_particle(), columns);
  return columns;
}

Sample Simulation::sample() const {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  Sample out;
  out.time = s.time;
  out.energies = s.energies();
  out.violation_position = s.dynamics->position_violation(s.time, s.state.q);
  out.violation_velocity = s.dynamics->velocity_violation(s.time, s.state.q, s.state.qd);
  out.broken_bonds = s.broken_bonds;
  // damage over all particles
  std::vector<float> damage;
  double sum = 0.0;
  long count = 0;
  for (const auto& flex : s.model->flex_bodies) {
    flex->damage(damage);
    for (float d : damage) {
      sum += d;
      out.max_damage = std::max(out.max_damage, static_cast<double>(d));
    }
    count += static_cast<long>(damage.size());
  }
  out.mean_damage = count ? sum / count : 0.0;
  for (const auto& contact : s.model->contacts) {
    const ContactTotals totals = contact->totals(s.state.q, s.state.qd);
    out.contact_force_total += totals.normal_force;
    out.contact_count += totals.active;
  }
  for (const auto& p : s.model->probes) {
    if (p.is_particle()) {
      const int c = p.particle_coordinate;
      out.probe_values.insert(out.probe_values.end(), {s.state.q[c], s.state.q[c + 1], s.state.qd[c], s.state.qd[c + 1]});
    } else {
      const Vec2 x = p.point.position(s.state.q);
      const Vec2 v = p.point.velocity(s.state.q, s.state.qd);
      out.probe_values.insert(out.probe_values.end(), {x.x(), x.y(), v.x(), v.y(), p.point.angle(s.state.q),
                                                       p.point.angular_velocity(s.state.qd)});
    }
  }
  return out;
}

Vec2 Simulation::probe_position(int index) const {
  const Impl& s = *impl_;
  const auto& p = s.model->probes.at(static_cast<size_t>(index));
  if (p.is_particle()) return Vec2(s.state.q[p.particle_coordinate], s.state.q[p.particle_coordinate + 1]);
  return p.point.position(s.state.q);
}

}  // namespace periflex
