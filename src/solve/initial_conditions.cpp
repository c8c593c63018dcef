// The start of a run: the state from the model's initial values, the step checked against the
// stability bound, positions and velocities brought onto the constraints, and the energy
// reference of the balance and the divergence check.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace periflex {

namespace {
using simulation_parts::number;
}  // namespace

void Simulation::Impl::initialize() {
  state.q = model->q0;
  state.qd = model->qd0;
  saved_current = false;
  state.work.setZero();
  time = 0.0;
  clock.reset(0.0, live.dt);
  steps = 0;
  fracture_energy = 0.0;
  dynamics->impose_prescribed(0.0, state.q, state.qd);

  // a contact stiffness that alone makes the step unstable is bad input: name it
  check_contact_steps();
  // explicit integration of particles is bounded by their critical step: a step the input chose
  // above it is bad input, named where it was set (scene line, --set or --dt), unless the input
  // asked to run past it; a step changed while running (the GUI's live settings) is a numerical stop
  if (past_stable_step() && !unstable_allowed()) {
    const std::string remedy = "lower solver.dt below " + number(allowed_step()) + " or set solver.auto_substep = true";
    if (live.dt == scene.solver.dt)
      throw InputError(scene.locate("solver.dt"), stability_message(live.dt) + "; " + remedy);
    throw NumericalError({"time step", 0, 0.0, stability_message(live.dt), remedy});
  }

  // consistent initial conditions: positions (Newton), then velocities
  const CorrectionDef& c = scene.solver.correction;
  const double tolerance = std::min(c.tolerance > 0.0 ? c.tolerance : 1e-10, 1e-10 * model->length_scale);
  const Eigen::VectorXd q_declared = state.q, qd_declared = state.qd;
  const double residual = dynamics->project_positions(0.0, state.q, tolerance, std::max(50, c.max_iterations));
  if (residual > 1e3 * tolerance) {
    throw NumericalError({"initial constraint violation", 0, 0.0,
                          "the initial positions cannot be brought onto the constraints (max |Phi| = " +
                              number(residual) + ", worst: '" + dynamics->worst_constraint(0.0, state.q) + "')",
                          "correct the initial positions, joint points or lengths in the scene"});
  }
  dynamics->project_velocities(0.0, state.q, state.qd);
  info.initial_position_correction = (state.q - q_declared).cwiseAbs().maxCoeff();
  info.initial_velocity_correction = (state.qd - qd_declared).cwiseAbs().maxCoeff();
  if (state.q.size() == 0) info.initial_position_correction = info.initial_velocity_correction = 0.0;

  // energy reference for the balance and for the divergence check
  initial_gravity = gravity_energy();
  initial_total = kinetic_energy() + initial_gravity + elastic_energy();
  double weight = 0.0;
  for (int c2 = 0; c2 < model->coordinate_count; ++c2) weight += std::abs(model->gravity_force[c2]);
  energy_scale = std::max(std::abs(kinetic_energy()) + std::abs(elastic_energy()) + weight * model->length_scale,
                          1e-12);
  integrator->reset();
  passage = PassageWatch{};
  passage.rows.reserve(model->constraint_rows);  // filled while passing a singular position
  passage.entry_q = state.q;
  passage.seen_changes = dynamics->rank_changes();
  passage.stable_dependent = dynamics->dropped_rows().size();
  initialized = true;
}

}  // namespace periflex
