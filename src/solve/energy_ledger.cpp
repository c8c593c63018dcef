// The energy ledger: kinetic, elastic and gravity energy at the current state, and the balance
// against the work fed in, the energy dissipated and released by fracture since t = 0.
#include "solve/simulation_impl.h"

namespace periflex {

double Simulation::Impl::kinetic_energy() const {
  return 0.5 * (model->mass.array() * state.qd.array().square()).sum();
}

double Simulation::Impl::elastic_energy() const {
  double e = 0.0;
  for (const auto& f : model->forces) e += f->potential_energy(state.q);
  for (const auto& flex : model->flex_bodies) e += flex->potential_energy(state.q);
  for (const auto& contact : model->contacts) e += contact->potential_energy(state.q);
  return e;
}

double Simulation::Impl::gravity_energy() const { return -model->gravity_force.dot(state.q); }

Energies Simulation::Impl::energies() const {
  Energies e;
  e.kinetic = kinetic_energy();
  e.potential_gravity = gravity_energy();
  e.potential_elastic = elastic_energy();
  e.dissipated = state.work[kWorkDissipated];
  e.fracture = fracture_energy;
  e.external_work = state.work[kWorkExternal];
  e.driver_work = state.work[kWorkDriver];
  e.balance = e.kinetic + e.potential_gravity + e.potential_elastic + e.dissipated + e.fracture - e.external_work -
              e.driver_work - initial_total;
  return e;
}

}  // namespace periflex
