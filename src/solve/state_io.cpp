// Save and restore of the whole live state (SimState), and the form of it written to checkpoint
// files: velocity Verlet's cached acceleration is stored xor'ed with its prediction (one evaluation
// at the saved state) and restored exactly.
#include "solve/simulation_impl.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace periflex {

namespace {
// a ^= b, value by value on the bit patterns (its own inverse)
void xor_bits(Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  for (Eigen::Index i = 0; i < a.size() && i < b.size(); ++i) {
    uint64_t x, y;
    std::memcpy(&x, &a[i], sizeof x);
    std::memcpy(&y, &b[i], sizeof y);
    x ^= y;
    std::memcpy(&a[i], &x, sizeof x);
  }
}
}  // namespace

void Simulation::save_state(SimState& out) const {
  const TeamSizeScope team(impl_->scene.solver.threads);
  const Impl& s = *impl_;
  out.time = s.time;
  out.steps = s.steps;
  out.clock_origin = s.clock.origin();
  out.clock_dt = s.clock.dt();
  out.clock_steps = s.clock.steps();
  out.initialized = s.initialized;
  out.q = s.state.q;
  out.qd = s.state.qd;
  out.work = s.state.work;
  out.fracture_energy = s.fracture_energy;
  out.broken_bonds = s.broken_bonds;
  out.initial_total = s.initial_total;
  out.initial_gravity = s.initial_gravity;
  out.energy_scale = s.energy_scale;
  out.initial_position_correction = s.info.initial_position_correction;
  out.initial_velocity_correction = s.info.initial_velocity_correction;
  out.passage = s.passage;
  s.dynamics->save_rank(out.rank);
  s.integrator->save_cache(out.integrator);
  out.flex.resize(s.model->flex_bodies.size());
  for (size_t f = 0; f < out.flex.size(); ++f) s.model->flex_bodies[f]->save_state(out.flex[f]);
  out.contacts.resize(s.model->contacts.size());
  for (size_t c = 0; c < out.contacts.size(); ++c) s.model->contacts[c]->save_cache(out.contacts[c]);
}

// The prediction of velocity Verlet's cache: the state put in place and one evaluation that
// closes no step (no half-kick booked for a bond it breaks). What the evaluation changed stays:
// the callers put a state in place after it.
void Simulation::accelerations_at(const SimState& in, Eigen::VectorXd& out) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  restore_whole(in);
  for (auto& flex : s.model->flex_bodies) flex->set_step_end(std::numeric_limits<double>::quiet_NaN(), 0.0);
  Eigen::Vector3d power;
  s.dynamics->derivative(in.time, s.state.q, s.state.qd, out, power);
}

void Simulation::save_state_for_file(SimState& out) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  save_state(out);
  IntegratorCache& cache = out.integrator;
  // only a cache that holds an acceleration to predict (velocity Verlet after a step)
  const IntegratorTraits* saved_by = find_integrator(cache.name);
  if (saved_by == nullptr || !saved_by->keeps_end_acceleration || cache.vectors.size() != 1 || cache.scalars.empty() ||
      cache.scalars[0] == 0.0)
    return;
  Eigen::VectorXd guess;
  accelerations_at(out, guess);
  restore_whole(out);  // the run goes on from the state saved, whatever the evaluation changed
  xor_bits(cache.vectors[0], guess);
  cache.predicted = true;
}

void Simulation::restore_state(const SimState& in) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  if (!in.integrator.predicted) {
    restore_whole(in);
    return;
  }
  SimState whole = in;
  whole.integrator.predicted = false;
  Eigen::VectorXd guess;
  accelerations_at(whole, guess);
  xor_bits(whole.integrator.vectors[0], guess);
  restore_whole(whole);
}

void Simulation::restore_whole(const SimState& in) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  const SystemModel& m = *s.model;
  // a state of another model is refused before anything changes
  const auto n = static_cast<Eigen::Index>(m.coordinate_count);
  if (in.q.size() != n || in.qd.size() != n || in.flex.size() != m.flex_bodies.size() ||
      in.contacts.size() != m.contacts.size()) {
    throw std::invalid_argument("the state does not belong to this model (" + std::to_string(in.q.size()) +
                                " coordinates, " + std::to_string(in.flex.size()) + " flexible bodies; the model has " +
                                std::to_string(n) + " and " + std::to_string(m.flex_bodies.size()) + ")");
  }
  for (size_t f = 0; f < in.flex.size(); ++f) m.flex_bodies[f]->restore_state(in.flex[f]);
  for (size_t c = 0; c < in.contacts.size(); ++c) m.contacts[c]->restore_cache(in.contacts[c]);
  s.dynamics->restore_rank(in.rank);
  s.state.q = in.q;
  s.state.qd = in.qd;
  s.state.work = in.work;
  s.time = in.time;
  s.steps = in.steps;
  // the clock as it was; a step size changed since (live settings) counts from the restored time
  s.clock.restore(in.clock_origin, in.clock_dt, in.clock_steps);
  if (in.clock_dt != s.live.dt) s.clock.reset(s.time, s.live.dt);
  s.initialized = in.initialized;
  s.fracture_energy = in.fracture_energy;
  s.broken_bonds = in.broken_bonds;
  s.initial_total = in.initial_total;
  s.initial_gravity = in.initial_gravity;
  s.energy_scale = in.energy_scale;
  s.info.initial_position_correction = in.initial_position_correction;
  s.info.initial_velocity_correction = in.initial_velocity_correction;
  s.passage = in.passage;
  s.saved_current = false;  // the fallback copy is of the state replaced
  s.passage.rows.reserve(m.constraint_rows);
  s.integrator->restore_cache(in.integrator);
}

}  // namespace periflex
