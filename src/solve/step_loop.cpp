// One step of the run: sub-steps of the integrator, prescribed motion, the rank after the step,
// the projection onto the constraints, fracture at the accepted positions, the watches, and the
// roll back to the last good state on a numerical failure.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <utility>

#include "core/error.h"
#include "core/parallel_chunks.h"

namespace periflex {

namespace {
using simulation_parts::Clock;
using simulation_parts::number;
using simulation_parts::since;
// Relative pivot below which the Jacobian counts as nearly singular when explaining a failure.
constexpr double kNearSingular = 1e-4;
}  // namespace

void Simulation::Impl::advance(double t_end) {
  const double h = t_end - time;
  // keep the last good state: nothing non-finite leaves the solver. After an accepted step the
  // divergence check has copied it already; otherwise copy into the kept buffers (no allocation)
  if (!saved_current) {
    saved.q.resize(state.q.size());
    saved.qd.resize(state.qd.size());
    parallel_chunks(state.q.size(), [&](int64_t, int64_t begin, int64_t end) {
      std::copy(state.q.data() + begin, state.q.data() + end, saved.q.data() + begin);
      std::copy(state.qd.data() + begin, state.qd.data() + end, saved.qd.data() + begin);
    });
    saved.work = state.work;
  }
  saved_current = false;
  const double saved_time = time;
  const auto start = Clock::now();
  const double forces0 = dynamics->force_seconds(), constraints0 = dynamics->constraint_seconds();
  double fracture_seconds = 0.0;
  try {
    // the mouse's anchor waits while it pulls harder than its limit
    if (auto& mouse = dynamics->mouse_spring()) hold_anchor_within_force(*mouse, time, h, state.q, grip.max_force);
    const int n = substeps_for(h);
    const double t0 = time;
    for (int k = 0; k < n; ++k) {
      const double t_next = (k + 1 == n) ? t_end : t0 + h * (k + 1) / n;
      const double step = t_next - time;
      const bool shake = integrator->is_symplectic() && dynamics->correction().method == CorrectionDef::Method::kProjection;
      if (shake) step_start.q = state.q;
      // velocity Verlet's evaluation at the end of the step is followed by a half-kick
      const double kick = integrator->traits().closing_kick;
      for (auto& flex : model->flex_bodies) flex->set_step_end(time + step, kick * step);
      integrator->step(*dynamics, time, step, state);
      time = t_next;
      dynamics->impose_prescribed(time, state.q, state.qd);
      // large systems: the rank of the bodies' small system after each step; the dependent
      // rows are derived again when it changed (small systems find it at every solve)
      if (dynamics->update_rank(time, state.q)) integrator->reset();

      // coordinate projection after the step
      const CorrectionDef& c = dynamics->correction();
      if (c.method == CorrectionDef::Method::kProjection && dynamics->has_constraints()) {
        // symplectic integrators: SHAKE then RATTLE. The position correction runs along the
        // constraint normals at the start of the step and is a change of the velocity that
        // drifted, so the velocity takes it too before its own projection. A correction along
        // the normals at the end (the nearest point) instead turns part of the centripetal
        // velocity into tangential speed: energy grows by (h v / L)^2 per step.
        if (shake) unprojected.q = state.q;
        const double residual =
            shake ? dynamics->project_positions_from(time, step_start.q, state.q, c.tolerance, c.max_iterations)
                  : dynamics->project_positions(time, state.q, c.tolerance, c.max_iterations);
        if (shake) state.qd += (state.q - unprojected.q) / step;
        if (residual > 1e3 * c.tolerance) {
          throw NumericalError({"constraint violation", -1, time,
                                "the projection did not converge (max |Phi| = " + number(residual) + " in '" +
                                    dynamics->worst_constraint(time, state.q) + "')",
                                "lower solver.dt or raise solver.correction.max_iterations"});
        }
        dynamics->project_velocities(time, state.q, state.qd);
        integrator->reset();
      }

      // fracture after each accepted step (timed only where there is something to break)
      if (!model->flex_bodies.empty()) {
        const auto fracture_start = Clock::now();
        for (auto& flex : model->flex_bodies) {
          if (!flex->fracture_enabled()) continue;
          const FractureUpdate update =
              flex->breaks_in_evaluation() ? flex->take_evaluation_breaks() : flex->update_fracture(state.q);
          fracture_energy += update.energy_released;
          broken_bonds += update.bonds_broken;
          if (update.forces_stale) integrator->reset();
        }
        fracture_seconds += since(fracture_start);
      }
    }
    ++steps;
    check_divergence();
    if (dynamics->monitors_rank()) check_passage();
    // accepted: the state the check copied is the next step's fallback
    std::swap(saved.q, checked.q);
    std::swap(saved.qd, checked.qd);
    saved.work = state.work;
    saved_current = true;
  } catch (const NumericalError& error) {
    NumericalDiagnostic d = error.diagnostic();
    if (d.step < 0) d.step = steps + 1;
    if (d.time == 0.0) d.time = time;
    // a run past the stable step on purpose: the failure is the divergence it was run to show
    if (past_stable_step()) {
      d.cause = stability_message(live.dt) + ", run past it on purpose (solver.allow_unstable): the explicit step "
                "diverged, as it must; " + d.cause;
      d.remedy = "lower solver.dt below " + number(allowed_step()) + " s to run stably";
    }
    state.q = saved.q;
    state.qd = saved.qd;
    state.work = saved.work;
    time = saved_time;
    integrator->reset();
    // a mechanism that locks shows a (nearly) singular Jacobian at the last good state
    if (dynamics->has_constraints() && d.quantity != "constraint Jacobian") {
      const auto names = dynamics->nearly_dependent_blocks(time, state.q, kNearSingular);
      if (!names.empty()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "'" : ", '") + n + "'";
        d.cause += "; the constraint Jacobian is nearly singular at t = " + number(time) + " (dependent: " + list +
                   "): the mechanism reaches a toggle or locked position";
        d.remedy = "change the geometry or the driver so the mechanism avoids this position";
      }
    }
    throw NumericalError(d);
  }
  const double total = since(start);
  const double forces = dynamics->force_seconds() - forces0, constraints = dynamics->constraint_seconds() - constraints0;
  timing.forces += forces;
  timing.constraints += constraints;
  timing.fracture += fracture_seconds;
  timing.integration += std::max(0.0, total - forces - constraints - fracture_seconds);
}

}  // namespace periflex
