// The Simulation's inside, shared by the files that hold its parts (simulation.cpp is the
// facade): the model, the state, the live settings, the watches and the energy reference, with
// the member functions each part defines. Not a public header: only src/solve includes it.
#pragma once

#include <chrono>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/sim_time.h"
#include "core/thread_pool.h"
#include "model/system_model.h"
#include "solve/dynamics.h"
#include "solve/integrator.h"
#include "solve/mouse_grip.h"
#include "solve/simulation.h"

namespace periflex {
namespace simulation_parts {

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline std::string number(double v) {
  std::ostringstream out;
  out.precision(3);
  out << v;
  return out.str();
}

// Steps between checks of the elastic energy (it costs about one force evaluation).
constexpr long kElasticCheckInterval = 64;

}  // namespace simulation_parts

struct Simulation::Impl {
  SceneDef scene;
  std::unique_ptr<SystemModel> model;
  std::unique_ptr<Dynamics> dynamics;
  std::unique_ptr<Integrator> integrator;
  ModelInfo info;
  LiveSettings live;

  OdeState state;
  OdeState saved;                  // the state before the step in progress (kept allocated)
  // the state check_divergence passed, copied in its pass over the coordinates: the next step's
  // `saved` once the step is accepted (a swap, not a copy). saved_current: `saved` is the state
  // as it stands (false after anything outside a step changed it)
  OdeState checked;
  bool saved_current = false;
  OdeState step_start, unprojected;  // positions at the step's start and before its projection (SHAKE)
  std::vector<double> chunk_sums;  // partial sums of check_divergence, per chunk
  double time = 0.0;               // clock.time(), or the exact time a step landed on
  SimClock clock;
  long steps = 0;
  bool initialized = false;
  double fracture_energy = 0.0;
  long broken_bonds = 0;
  std::vector<ContactPoint> contact_points;  // scratch of fill_snapshot
  double initial_total = 0.0;      // kinetic + potential at t = 0
  double initial_gravity = 0.0;    // potential of gravity at t = 0
  double energy_scale = 0.0;       // for the divergence check
  double critical_step = 0.0;      // min over the flexible bodies (0: none)
  GripLimits grip;                 // of the mouse's grab of a flexible body (mouse_grip.h)
  bool grip_hard = false;          // the grab is a hard one (MouseSpring::hard)
  // passages through singular positions (rank monitoring): the energy balance when the rank
  // first changed or the Jacobian came near losing it, checked when the rank is back and the
  // position left behind, so a jump onto another branch is no silent one
  PassageWatch passage;
  Timing timing;
  mutable std::shared_ptr<const SceneGeometry> geometry;

  // --- set-up -------------------------------------------------------------------------
  // the model report: counts, critical step, active modules, warnings (model_report.cpp)
  void build_info();

  // --- the stability bound of explicit steps (stability_bound.cpp) ---------------------
  double allowed_step() const;
  // A step above the allowed one by less than the rounding of `check`'s printout (6 significant
  // digits: up to 5e-6 relative) is the allowed step given back by a user or a script: accepted.
  bool step_exceeds_allowed(double dt) const;
  bool stability_bound_applies() const;
  // sub-steps only when asked for (solver.auto_substep): a step past the limit run on purpose
  // (solver.allow_unstable) is taken whole
  int substeps_for(double h) const;
  // A step above the allowed one runs only when asked for (solver.allow_unstable, or the
  // window's dt confirmed past the limit): to watch an explicit step diverge.
  bool unstable_allowed() const;
  bool past_stable_step() const;
  std::string stability_message(double dt) const;
  // Throws InputError at the contact whose stiffness lowers the critical step below solver.dt
  // when the bonds alone would allow it (without auto_substep).
  void check_contact_steps() const;

  // When bonds past s0 break (docs/peridynamics.md §3): in the force evaluation that first sees
  // them with the integrators that evaluate forces only at accepted positions; the multi-stage
  // ones hold every intact bond in their trial stages (a stage that dropped a bond, which the
  // step's weights then count only in part, would spoil the energy balance) and break them at
  // the accepted positions after the step.
  void choose_fracture_order() {
    using Timing = PdBody::BreakTiming;
    const Timing timing = integrator->traits().breaks_in_evaluation ? Timing::kInEvaluation : Timing::kAfterStep;
    for (auto& flex : model->flex_bodies) flex->set_break_timing(timing);
  }

  // --- stepping -----------------------------------------------------------------------
  // consistent initial conditions and the energy reference (initial_conditions.cpp)
  void initialize();
  // one step from `time` to exactly t_end (h = t_end - time, split into sub-steps if needed;
  // step_loop.cpp)
  void advance(double t_end);
  // --- the watches ----------------------------------------------------------------------
  // non-finite state, constraint drift, energy growth (divergence_check.cpp)
  void check_divergence();
  // passages through singular positions (passage_watch.cpp)
  void check_passage();
  bool drift_allowed() const;
  double branch_energy_allowed(double span, double& own) const;
  // --- the energy ledger (energy_ledger.cpp) --------------------------------------------
  Energies energies() const;
  double kinetic_energy() const;
  double elastic_energy() const;
  double gravity_energy() const;
};

}  // namespace periflex
