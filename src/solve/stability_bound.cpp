// The stability bound of explicit steps on particles: the largest step allowed (dt_safety times
// the critical step of the bonds and contacts), when a step past it is split, refused or run on
// purpose, and the contact whose stiffness alone makes a step unstable.
#include "solve/simulation_impl.h"

#include <cmath>

#include "core/error.h"

namespace periflex {

namespace {
using simulation_parts::number;
}  // namespace

double Simulation::Impl::allowed_step() const { return scene.solver.dt_safety * critical_step; }

bool Simulation::Impl::step_exceeds_allowed(double dt) const { return dt > allowed_step() * (1.0 + 1e-5); }

bool Simulation::Impl::stability_bound_applies() const {
  return critical_step > 0.0 && integrator->is_explicit() && !integrator->is_adaptive();
}

int Simulation::Impl::substeps_for(double h) const {
  if (!scene.solver.auto_substep || !stability_bound_applies() || !step_exceeds_allowed(h)) return 1;
  return static_cast<int>(std::ceil(h / allowed_step() * (1 - 1e-12)));
}

bool Simulation::Impl::unstable_allowed() const { return scene.solver.allow_unstable || live.allow_unstable; }

bool Simulation::Impl::past_stable_step() const {
  return stability_bound_applies() && !scene.solver.auto_substep && step_exceeds_allowed(live.dt);
}

std::string Simulation::Impl::stability_message(double dt) const {
  return "solver.dt = " + number(dt) + " s is above dt_safety * critical step = " + number(allowed_step()) +
         " s (critical step " + number(critical_step) + " s) of the explicit " + integrator->name() +
         " integrator";
}

void Simulation::Impl::check_contact_steps() const {
  if (!stability_bound_applies() || scene.solver.auto_substep || unstable_allowed()) return;
  const double safety = scene.solver.dt_safety;
  for (const auto& contact : model->contacts) {
    const double with = contact->critical_time_step(), without = contact->bond_critical_time_step();
    if (!(live.dt > safety * with) || live.dt > safety * without) continue;
    const ContactDef& def = contact->def();
    SourceLocation where = def.stiffness_where.line > 0 ? def.stiffness_where : def.where;
    where.key = "contact." + def.name + ".stiffness";
    // the stiffness at which this dt is the bound: 1/dt^2 = 1/dt_bonds^2 + k / (k_now dt_contact^2)
    const double room = 1.0 / (live.dt * live.dt / (safety * safety)) - 1.0 / (without * without);
    const double contact_part = 1.0 / (with * with) - 1.0 / (without * without);
    const double stable = contact->stiffness() * room / contact_part;
    throw InputError(where, "contact stiffness " + number(contact->stiffness()) + " N/m lowers the critical step to " +
                                number(with) + " s, and solver.dt = " + number(live.dt) + " s is above dt_safety * " +
                                number(with) + " = " + number(safety * with) + " s of the explicit " +
                                integrator->name() + " integrator; lower the stiffness below about " +
                                number(stable) + " N/m, lower solver.dt below " + number(safety * with) +
                                " s or set solver.auto_substep = true");
  }
}

}  // namespace periflex
