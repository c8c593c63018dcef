// The Simulation: assembles the model, keeps the state, steps it with the chosen integrator and
// correction, books the energies, watches for divergence, and reports samples and snapshots.
// This file is the facade (construction, the clock, live settings); the parts live beside it:
// model_report, stability_bound, initial_conditions, step_loop, divergence_check, passage_watch,
// energy_ledger, state_io, sample, snapshot_fill, mouse_spring and knife (.cpp), sharing
// simulation_impl.h.
#include "solve/simulation.h"


#include <memory>
#include <utility>

#include "core/error.h"
#include "solve/simulation_impl.h"

namespace periflex {

namespace {
using simulation_parts::number;
}  // namespace

Simulation::Simulation(const SceneDef& scene) : impl_(std::make_unique<Impl>()) {
  // solver.threads sets the team of this simulation's own calls (0: the calling thread's
  // OpenMP setting); the calling thread's setting itself is left alone
  const TeamSizeScope team(scene.solver.threads);
  Impl& s = *impl_;
  s.scene = scene;
  if (!(scene.solver.dt > 0.0)) throw InputError({scene.path, 0, 0, "solver.dt"}, "solver.dt must be > 0");
  if (!(scene.solver.dt_safety > 0.0)) {
    throw InputError({scene.path, 0, 0, "solver.dt_safety"}, "solver.dt_safety must be > 0");
  }
  s.model = build_system_model(scene);
  s.dynamics = std::make_unique<Dynamics>(*s.model);
  s.dynamics->set_correction(scene.solver.correction);
  s.dynamics->analyse(0.0);
  try {
    s.integrator = make_integrator(scene.solver.integrator, scene.solver);
  } catch (const InputError& e) {
    throw InputError({scene.path, 0, 0, "solver.integrator"}, e.detail());
  }
  s.live.integrator = s.integrator->name();
  s.choose_fracture_order();
  s.live.dt = scene.solver.dt;
  s.live.allow_unstable = scene.solver.allow_unstable;
  s.live.correction = scene.solver.correction;
  s.live.fracture = true;
  for (const auto& flex : s.model->flex_bodies) {
    s.live.bond_damping = flex->bond_damping();
    s.live.global_damping = flex->global_damping();
    s.live.fracture = flex->fracture_enabled();
  }
  s.state.q = s.model->q0;
  s.state.qd = s.model->qd0;
  s.build_info();
}

Simulation::~Simulation() = default;

const SceneDef& Simulation::scene() const { return impl_->scene; }
const ModelInfo& Simulation::info() const { return impl_->info; }
double Simulation::time() const { return impl_->time; }
const Eigen::VectorXd& Simulation::coordinates() const { return impl_->state.q; }
const Eigen::VectorXd& Simulation::velocities() const { return impl_->state.qd; }
long Simulation::step_count() const { return impl_->steps; }
double Simulation::end_time() const { return impl_->scene.solver.end_time; }
Simulation::Timing Simulation::timing() const { return impl_->timing; }

void Simulation::initialize() {
  const TeamSizeScope team(impl_->scene.solver.threads);
  impl_->initialize();
}

void Simulation::step() {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  if (!s.initialized) s.initialize();
  s.advance(s.clock.next_time());
  s.clock.tick();
}

bool Simulation::step_toward(double t) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  if (!s.initialized) s.initialize();
  const double dt = s.clock.dt();
  if (time_reached(s.time, t, dt)) return true;
  // a plain step while it stays short of t; else a step shortened (or stretched by round-off)
  // to land on t exactly, from where the clock counts again
  const double plain = s.clock.next_time();
  if (plain < t - time_tolerance(dt, t)) {
    s.advance(plain);
    s.clock.tick();
    return false;
  }
  s.advance(t);
  s.clock.land(t);
  return true;
}

void Simulation::advance_to(double t) {
  while (!step_toward(t)) {
  }
}

bool Simulation::reached(double t) const { return time_reached(impl_->time, t, impl_->clock.dt()); }
LiveSettings Simulation::settings() const { return impl_->live; }

void Simulation::apply(const LiveSettings& settings) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  // a new integrator, time step or correction takes effect from the next step
  std::unique_ptr<Integrator> next;
  if (!settings.integrator.empty() && settings.integrator != s.integrator->name()) {
    next = make_integrator(settings.integrator, s.scene.solver);
  }
  const double dt = settings.dt > 0.0 ? settings.dt : s.live.dt;
  // try the candidate integrator in place (the stability bound depends on it); a refusal
  // puts the running one back. With the same integrator nothing is swapped.
  if (next) std::swap(next, s.integrator);
  const bool allowed = settings.allow_unstable || s.scene.solver.allow_unstable;
  if (s.stability_bound_applies() && s.step_exceeds_allowed(dt) && !s.scene.solver.auto_substep && !allowed) {
    const std::string message = s.stability_message(dt);
    if (next) std::swap(next, s.integrator);  // keep the running configuration
    throw InputError({"", 0, 0, "solver.dt"}, message + "; lower it below " + number(s.allowed_step()) +
                                                  " or enable solver.auto_substep");
  }
  s.live.integrator = s.integrator->name();
  s.choose_fracture_order();
  if (dt != s.live.dt) s.clock.reset(s.time, dt);
  s.live.dt = dt;
  s.live.allow_unstable = allowed;
  s.live.correction = settings.correction;
  s.dynamics->set_correction(settings.correction);
  s.live.bond_damping = settings.bond_damping;
  s.live.global_damping = settings.global_damping;
  s.live.fracture = settings.fracture;
  for (auto& flex : s.model->flex_bodies) {
    flex->set_bond_damping(settings.bond_damping);
    flex->set_global_damping(settings.global_damping);
    flex->set_fracture_enabled(settings.fracture);
  }
  s.integrator->reset();
  s.build_info();
}

}  // namespace periflex
