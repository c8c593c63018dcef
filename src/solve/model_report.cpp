// The model report (ModelInfo): what the scene holds, the critical step, which modules run and the
// trouble foreseeable at set-up (a step past the stable one, bodies that start overlapping, a
// horizon below two grid spacings, redundant constraints).
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>

namespace periflex {

namespace {
using simulation_parts::number;
}  // namespace

void Simulation::Impl::build_info() {
  const SystemModel& m = *model;
  info.bodies = static_cast<int>(m.bodies.size());
  info.virtual_bodies = static_cast<int>(std::count_if(m.bodies.begin(), m.bodies.end(),
                                                       [](const BodyDef& b) { return b.is_virtual; }));
  info.joints = m.joints;
  info.drivers = m.drivers;
  info.force_elements = static_cast<int>(m.forces.size());
  info.probes = static_cast<int>(m.probes.size());
  info.flex_bodies = static_cast<int>(m.flex_bodies.size());
  info.particles = 0;
  info.bonds = 0;
  critical_step = 0.0;
  for (const auto& flex : m.flex_bodies) {
    info.particles += flex->particle_count();
    info.bonds += flex->bond_count();
    const double crit = flex->critical_time_step();
    if (crit > 0.0) critical_step = critical_step > 0.0 ? std::min(critical_step, crit) : crit;
  }
  // a contact's stiffness adds to the bonds' on the particles it touches
  for (const auto& contact : m.contacts) {
    const double crit = contact->critical_time_step();  // infinite between massless bodies
    if (crit > 0.0 && std::isfinite(crit)) critical_step = critical_step > 0.0 ? std::min(critical_step, crit) : crit;
  }
  info.coordinates = m.coordinate_count;
  info.constraint_equations = m.constraint_rows;
  info.redundant_equations = static_cast<int>(dynamics->dropped_rows().size());
  info.redundant_constraints = dynamics->dropped_blocks();
  // a held zero-inertia angle is no degree of freedom: nothing determines or moves it
  info.degrees_of_freedom = m.coordinate_count - static_cast<int>(m.prescribed.size()) -
                            static_cast<int>(dynamics->held_rotations().size()) - dynamics->independent_rows();
  info.critical_time_step = critical_step;

  // what runs: only the parts this scene needs
  auto& mods = info.active_modules;
  mods.clear();
  if (!m.bodies.empty()) mods.push_back("rigid_bodies");
  if (m.gravity.norm() > 0.0 && m.gravity_force.norm() > 0.0) mods.push_back("gravity");
  if (!m.forces.empty()) mods.push_back("force_elements");
  if (dynamics->has_constraints()) mods.push_back("constraint_solver");
  if (!m.flex_bodies.empty()) mods.push_back("pd_forces");
  bool fracture = false, bond_damping = false, global_damping = false;
  for (const auto& flex : m.flex_bodies) {
    fracture |= flex->fracture_enabled();
    bond_damping |= flex->bond_damping() != 0.0;
    global_damping |= flex->global_damping() != 0.0;
  }
  if (fracture) mods.push_back("pd_fracture");
  if (bond_damping) mods.push_back("pd_bond_damping");
  if (global_damping) mods.push_back("pd_global_damping");
  if (!m.attachments.empty()) mods.push_back("rigid_flexible_joints");
  if (!m.prescribed.empty()) mods.push_back("prescribed_motion");
  if (!m.contacts.empty()) mods.push_back("contact");

  // foreseeable trouble
  auto& w = info.warnings;
  w.clear();
  if (stability_bound_applies() && step_exceeds_allowed(scene.solver.dt)) {
    w.push_back(stability_message(scene.solver.dt) +
                (scene.solver.auto_substep ? "; each step is split into " +
                                                 std::to_string(substeps_for(scene.solver.dt)) + " sub-steps"
                 : unstable_allowed()      ? "; run anyway (solver.allow_unstable): expect it to diverge"
                                           : "; lower solver.dt or set solver.auto_substep = true"));
  }
  // bodies that start inside each other are pushed apart at once, with the full penalty force
  for (const auto& contact : m.contacts) {
    const long overlapping = contact->totals(m.q0, m.qd0).active;
    if (overlapping > 0)
      w.push_back("contact '" + contact->name() + "': " + std::to_string(overlapping) +
                  " contact(s) active at t = 0: the bodies start overlapping and are pushed apart at once");
  }
  for (size_t k = 0; k < m.flex_bodies.size(); ++k) {
    const PdBody& flex = *m.flex_bodies[k];
    for (const auto& text : flex.warnings()) w.push_back("flexible body '" + flex.name() + "': " + text);
    if (flex.horizon() < 2.0 * flex.grid_spacing() * (1 - 1e-12)) {
      w.push_back("flexible body '" + flex.name() + "': horizon " + number(flex.horizon()) +
                  " is below 2 grid spacings; raise horizon_ratio to 3");
    }
  }
  if (!info.redundant_constraints.empty()) {
    std::string names;
    for (const auto& n : info.redundant_constraints) names += (names.empty() ? "" : ", ") + n;
    w.push_back(std::to_string(info.redundant_equations) + " redundant constraint equation(s) at t = 0 in: " + names +
                (dynamics->monitors_rank() ? std::string(" (left out only while they stay dependent: the rank is found "
                                                         "again at every ") +
                                                 (dynamics->dense() ? "solve)" : "step)")
                                           : std::string(" (dropped for the run)")));
  }
}

}  // namespace periflex
