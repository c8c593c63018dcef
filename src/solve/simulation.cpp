// The Simulation: assembles the model, keeps the state, steps it with the chosen integrator and
// correction, books the energies, watches for divergence, and reports samples and snapshots.
#include "solve/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/parallel_chunks.h"
#include "core/sim_time.h"
#include "model/system_model.h"
#include "solve/dynamics.h"
#include "solve/integrator.h"
#include "solve/mouse_grip.h"

namespace periflex {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string number(double v) {
  std::ostringstream out;
  out.precision(3);
  out << v;
  return out.str();
}

// Bodies with fewer bonds than this send their bond pairs in snapshots.
constexpr long kDrawnBondLimit = 5000;
// Divergence bounds (documented in docs/solver.md): constraint violation above this fraction of
// the model size, kinetic energy above this multiple of the energy the model can hold.
constexpr double kViolationFraction = 0.05;
constexpr double kEnergyGrowth = 1e3;
// Relative pivot below which the Jacobian counts as nearly singular when explaining a failure.
constexpr double kNearSingular = 1e-4;
// Steps between checks of the elastic energy (it costs about one force evaluation).
constexpr long kElasticCheckInterval = 64;
// Energy-balance change across a passage through a singular position, relative to the energy
// scale, above which the motion is taken to have left its branch (on the double four-bar a
// passage costs at most a few 1e-6 of the scale with rk4 or dopri54; a switch of branch about
// 1e-2).
constexpr double kBranchEnergy = 1e-5;
// Symplectic integrators with projection have an energy error of their own that stays bounded
// but moves with the motion by more than that (symplectic Euler on the double four-bar at
// dt = 2.5e-4: 2.8e-5 of the scale across a dead point, as much as over the 0.04 s before it).
// For them a passage may move the balance by up to kDriftFactor times what it moved over as
// long a span just before the passage opened, provided that is at most kBranchEnergyCeiling of
// the scale (a tenth of what a switch costs on the double four-bar); a larger own error could
// hide a switch of branch, and the fixed threshold holds (the run stops: lower the step).
constexpr double kDriftFactor = 3.0;
constexpr double kBranchEnergyCeiling = 1e-3;
// Smallest scaled pivot of the acceleration solve (small systems), as a fraction of the largest
// one the run has seen, below which a step counts as passing a singular position even when no
// row was left out. With Baumgarte correction, or at steps that stride over the dead point, no
// stage may land within the rank threshold, yet the solve near the position amplifies the drift
// by 1 / pivot and can carry the motion onto another path. The pivot is of the mass-weighted
// Jacobian, so its level away from any singular position depends on the masses and lengths:
// 0.52-0.71 on the double four-bar, 0.10-0.15 on the four-bar crank-rocker with a crank ten
// times heavier, whose transmission angle never leaves 39-79 degrees. Hence a fraction of the
// best level: on the double four-bar the pivot falls by about 0.03 per step of 5e-3 s near a
// dead point, and 0.2 of the level opens a passage a few steps ahead of it (at 0.10-0.14) at
// the step sizes in use.
constexpr double kPassagePivotFraction = 0.2;
// The pivot threshold for naming the nearly dependent rows when a passage fails (relative to
// the largest pivot of the unweighted Jacobian).
constexpr double kPassagePivot = 0.1;
}  // namespace

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
  void build_info();
  double allowed_step() const { return scene.solver.dt_safety * critical_step; }
  // A step above the allowed one by less than the rounding of `check`'s printout (6 significant
  // digits: up to 5e-6 relative) is the allowed step given back by a user or a script: accepted.
  bool step_exceeds_allowed(double dt) const { return dt > allowed_step() * (1.0 + 1e-5); }
  bool stability_bound_applies() const {
    return critical_step > 0.0 && integrator->is_explicit() && !integrator->is_adaptive();
  }
  // sub-steps only when asked for (solver.auto_substep): a step past the limit run on purpose
  // (solver.allow_unstable) is taken whole
  int substeps_for(double h) const {
    if (!scene.solver.auto_substep || !stability_bound_applies() || !step_exceeds_allowed(h)) return 1;
    return static_cast<int>(std::ceil(h / allowed_step() * (1 - 1e-12)));
  }
  // A step above the allowed one runs only when asked for (solver.allow_unstable, or the
  // window's dt confirmed past the limit): to watch an explicit step diverge.
  bool unstable_allowed() const { return scene.solver.allow_unstable || live.allow_unstable; }
  bool past_stable_step() const {
    return stability_bound_applies() && !scene.solver.auto_substep && step_exceeds_allowed(live.dt);
  }
  std::string stability_message(double dt) const {
    return "solver.dt = " + number(dt) + " s is above dt_safety * critical step = " + number(allowed_step()) +
           " s (critical step " + number(critical_step) + " s) of the explicit " + integrator->name() +
           " integrator";
  }

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

  // Throws InputError at the contact whose stiffness lowers the critical step below solver.dt
  // when the bonds alone would allow it (without auto_substep).
  void check_contact_steps() const;

  // --- stepping -----------------------------------------------------------------------
  void initialize();
  // one step from `time` to exactly t_end (h = t_end - time, split into sub-steps if needed)
  void advance(double t_end);
  void check_divergence();
  void check_passage();
  bool drift_allowed() const;
  double branch_energy_allowed(double span, double& own) const;
  Energies energies() const;
  double kinetic_energy() const {
    return 0.5 * (model->mass.array() * state.qd.array().square()).sum();
  }
  double elastic_energy() const {
    double e = 0.0;
    for (const auto& f : model->forces) e += f->potential_energy(state.q);
    for (const auto& flex : model->flex_bodies) e += flex->potential_energy(state.q);
    for (const auto& contact : model->contacts) e += contact->potential_energy(state.q);
    return e;
  }
  double gravity_energy() const { return -model->gravity_force.dot(state.q); }
};

// ---------------------------------------------------------------------------------------
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

void Simulation::Impl::check_divergence() {
  // non-finite state, and the kinetic energy, in one pass: a NaN or infinity anywhere in q or qd
  // makes the sums non-finite (massless coordinates too: 0 * inf is NaN)
  // (per-chunk partial sums added in chunk order: the same bits on any thread count)
  const int64_t n = state.q.size();
  const double* pq = state.q.data();
  const double* pv = state.qd.data();
  const double* pm = model->mass.data();
  // the same pass copies the state, for the next step's fallback once this one is accepted
  checked.q.resize(n);
  checked.qd.resize(n);
  double* cq = checked.q.data();
  double* cv = checked.qd.data();
  chunk_sums.assign(3 * chunk_count(n), 0.0);
  parallel_chunks(n, [&](int64_t chunk, int64_t begin, int64_t end) {
    double q_zero = 0.0, v_zero = 0.0, twice_kinetic = 0.0;
#pragma omp simd reduction(+ : q_zero, v_zero, twice_kinetic)
    for (int64_t i = begin; i < end; ++i) {
      cq[i] = pq[i];
      cv[i] = pv[i];
      q_zero += pq[i] * 0.0;
      v_zero += pv[i] * 0.0;
      twice_kinetic += pm[i] * pv[i] * pv[i];
    }
    chunk_sums[3 * chunk] = q_zero;
    chunk_sums[3 * chunk + 1] = v_zero;
    chunk_sums[3 * chunk + 2] = twice_kinetic;
  });
  double q_sum = 0.0, v_sum = 0.0, kinetic2 = 0.0;
  for (size_t c = 0; c < chunk_sums.size(); c += 3) {
    q_sum += chunk_sums[c];
    v_sum += chunk_sums[c + 1];
    kinetic2 += chunk_sums[c + 2];
  }
  if (!std::isfinite(q_sum) || !std::isfinite(v_sum)) {
    throw NumericalError({"state (positions / velocities)", steps, time, "a coordinate became NaN or infinite",
                          "lower solver.dt, use a higher-order integrator or enable constraint correction"});
  }
  // constraint drift beyond a fraction of the model size
  if (dynamics->has_constraints()) {
    const double limit = std::max(kViolationFraction * model->length_scale, 1e3 * dynamics->correction().tolerance);
    const double violation = dynamics->position_violation(time, state.q);
    if (!(violation <= limit)) {
      // the remedy depends on the correction in use: none, gains too high for the step, or neither
      const CorrectionDef& c = dynamics->correction();
      const double gain_step = std::max(c.alpha, c.beta) * live.dt;
      std::string remedy = "lower solver.dt; if the mechanism passes a toggle (singular) position, change its "
                           "geometry or driver";
      if (c.method == CorrectionDef::Method::kNone) {
        remedy = "enable solver.correction (baumgarte or projection) or lower solver.dt";
      } else if (c.method == CorrectionDef::Method::kBaumgarte && gain_step > 1.0) {
        remedy = "lower solver.correction.alpha and beta (now max(alpha, beta) * dt = " + number(gain_step) +
                 "; keep it below 1) or lower solver.dt";
      }
      throw NumericalError({"constraint violation", steps, time,
                            "max |Phi| = " + number(violation) + " exceeds " + number(limit) + " (in '" +
                                dynamics->worst_constraint(time, state.q) + "')",
                            remedy});
    }
  }
  // energy far beyond what the model holds and what was fed in: the kinetic energy every step
  // (cheap), the kinetic plus elastic energy every kElasticCheckInterval steps (an instability that
  // grows the positions while the velocities stay small, e.g. Verlet exactly at its limit)
  const double fed = std::abs(state.work[kWorkExternal]) + std::abs(state.work[kWorkDriver]);
  // a held mouse spring feeds its work a step late to the accounts: what it still holds counts
  // too, or a grab of a body at rest (which holds nothing) would look like a divergence
  const auto& mouse = dynamics->mouse_spring();
  const double held = mouse ? mouse->stored_energy(time, state.q) : 0.0;
  const double available = energy_scale + fed + held;
  const double kinetic = 0.5 * kinetic2;
  const bool check_elastic = steps % kElasticCheckInterval == 0;
  const double mechanical = check_elastic ? kinetic + elastic_energy() : kinetic;
  // a body falling far has turned that much potential of gravity into motion: not a divergence
  // (computed only when the cheap bound fails: it costs a pass over the coordinates)
  const auto released = [&] { return std::max(0.0, initial_gravity - gravity_energy()); };
  // the work loads did over the step just taken, which the accounts may not hold yet (symplectic
  // Euler books a step's work at the velocities it started from: none, for loads on a body at rest)
  const auto fed_in_step = [&] {
    double power = 0.0;
    for (const auto& f : model->forces) power += std::abs(f->external_power(state.q, state.qd, time));
    for (const auto& flex : model->flex_bodies) power += std::abs(flex->external_power(state.q, state.qd, time));
    return live.dt * power;
  };
  if (mechanical > kEnergyGrowth * available &&
      mechanical > kEnergyGrowth * (available + released() + fed_in_step())) {
    // explicit damping forces are themselves unstable once damping * dt is of order 1
    std::string damped;
    for (const auto& flex : model->flex_bodies) {
      if (flex->global_damping() > 0.0 || flex->bond_damping() > 0.0) damped = flex->name();
    }
    std::string remedy = "lower solver.dt (explicit stability) or check stiffnesses and loads";
    if (!damped.empty()) {
      remedy += ", or lower flex_body." + damped + ".global_damping / bond_damping (explicit damping needs "
                "global_damping * dt < 2)";
    }
    const std::string what = mechanical > kinetic ? "kinetic plus elastic energy " : "kinetic energy ";
    throw NumericalError({mechanical > kinetic ? "energy" : "kinetic energy", steps, time,
                          what + number(mechanical) + " J grew beyond " + number(kEnergyGrowth) +
                              " times the energy available (" + number(available) + " J)",
                          remedy});
  }
}

// Only symplectic integrators with projection keep a bounded energy error (the long-run energy
// tests hold them to it): there the change of the balance before a passage says what the
// integrator itself does across it. Dissipative schemes (HHT) and Baumgarte correction lose or
// gain energy without bound, so a drift before the passage vouches for nothing; they keep the
// fixed threshold.
bool Simulation::Impl::drift_allowed() const {
  return integrator->is_symplectic() && dynamics->correction().method == CorrectionDef::Method::kProjection;
}

// The largest change of the energy balance across a passage that lasted `span` seconds taken as
// the integrator's own error rather than a switch of branch; `own` is set to that error over
// `span` when it was too large to be allowed (0 otherwise).
double Simulation::Impl::branch_energy_allowed(double span, double& own) const {
  own = 0.0;
  const double fixed = kBranchEnergy * energy_scale;
  if (!drift_allowed()) return fixed;
  const double drift = passage.drift.change_over(span);
  if (kDriftFactor * drift > kBranchEnergyCeiling * energy_scale) {
    own = drift;
    return fixed;
  }
  return std::max(fixed, kDriftFactor * drift);
}

void Simulation::Impl::check_passage() {
  const long changes = dynamics->rank_changes();
  const auto& now = dynamics->dependent_now();
  const double pivot = dynamics->smallest_pivot();
  passage.best_pivot = std::max(passage.best_pivot, pivot);
  const bool near = pivot < kPassagePivotFraction * passage.best_pivot;
  if (changes != passage.seen_changes || near) {
    // the rank changed during this step, or the Jacobian is close to losing it: a singular
    // position is near
    passage.seen_changes = changes;
    if (!passage.open) {
      passage.open = true;
      passage.entry_time = time;
      passage.entry_balance = energies().balance;
      passage.rows.clear();
      // where it opened (into the kept buffer: no allocation), to name the rows that nearly
      // depend on the others if the check fails, even when none was left out
      passage.entry_q = state.q;
    }
    for (int r : now) {
      if (std::find(passage.rows.begin(), passage.rows.end(), r) == passage.rows.end()) passage.rows.push_back(r);
    }
    return;
  }
  if (!passage.open) {
    passage.stable_dependent = now.size();
    // the integrator's own energy error where nothing singular happens, sampled only where it
    // is used: one pass over the coordinates per step, or every kElasticCheckInterval steps
    // with flexible bodies (their elastic energy is a pass over the bonds)
    const bool due = model->flex_bodies.empty() || steps % kElasticCheckInterval == 0;
    if (due && drift_allowed()) passage.drift.record(time, energies().balance);
    return;
  }
  if (now.size() > passage.stable_dependent) return;
  // the rank is back: the motion must have carried on without a jump in the energy balance
  // (a switch of branch shows as energy gained or lost in a few steps)
  passage.open = false;
  passage.stable_dependent = now.size();
  const double jump = energies().balance - passage.entry_balance;
  double own = 0.0;
  const double allowed = branch_energy_allowed(time - passage.entry_time, own);
  // the span before the next passage is measured afresh
  passage.drift.clear();
  if (std::abs(jump) > allowed) {
    std::string names;
    std::vector<std::string> blocks = dynamics->blocks_of(passage.rows);
    const Eigen::VectorXd& entry_q = passage.entry_q.size() == state.q.size() ? passage.entry_q : state.q;
    for (const auto& n : dynamics->nearly_dependent_blocks(passage.entry_time, entry_q, kPassagePivot))
      if (std::find(blocks.begin(), blocks.end(), n) == blocks.end()) blocks.push_back(n);
    for (const auto& n : blocks) names += (names.empty() ? "'" : ", '") + n + "'";
    if (names.empty()) names = "none left out";
    throw NumericalError({"singular configuration", steps, time,
                          "the mechanism passed a singular position between t = " + number(passage.entry_time) +
                              " and " + number(time) + " s (dependent: " + names +
                              ") and its energy balance jumped by " + number(jump) +
                              " J: the motion may have left the physical branch" +
                              (own > 0.0 ? " (the integrator's own energy error, " + number(own) +
                                               " J over as long a span before it, is too large to tell)"
                                         : ""),
                          own > 0.0 ? "lower solver.dt, or use dopri54 with projection"
                                    : "change solver.dt, or use dopri54 with projection; if the position is a true "
                                      "lock, change the geometry or the driver"});
  }
}

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

// ---------------------------------------------------------------------------------------
Simulation::Simulation(const SceneDef& scene) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.scene = scene;
  // solver.threads caps the force evaluation's OpenMP team (0 keeps the runtime's default)
  if (scene.solver.threads > 0) omp_set_num_threads(scene.solver.threads);
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

void Simulation::save_state(SimState& out) const {
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

// The prediction of velocity Verlet's cache: the state put in place and one evaluation that
// closes no step (no half-kick booked for a bond it breaks). What the evaluation changed stays:
// the callers put a state in place after it.
void Simulation::accelerations_at(const SimState& in, Eigen::VectorXd& out) {
  Impl& s = *impl_;
  restore_whole(in);
  for (auto& flex : s.model->flex_bodies) flex->set_step_end(std::numeric_limits<double>::quiet_NaN(), 0.0);
  Eigen::Vector3d power;
  s.dynamics->derivative(in.time, s.state.q, s.state.qd, out, power);
}

void Simulation::save_state_for_file(SimState& out) {
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

void Simulation::initialize() { impl_->initialize(); }

void Simulation::step() {
  Impl& s = *impl_;
  if (!s.initialized) s.initialize();
  s.advance(s.clock.next_time());
  s.clock.tick();
}

bool Simulation::step_toward(double t) {
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

void Simulation::fill_snapshot(Snapshot& out) const {
  Impl& s = *impl_;
  const SystemModel& m = *s.model;
  const Eigen::VectorXd& q = s.state.q;
  const Eigen::VectorXd& qd = s.state.qd;

  // the constant part, built once
  if (!s.geometry) {
    auto g = std::make_shared<SceneGeometry>();
    g->scene_name = s.scene.name;
    SceneGeometry::Body ground;
    ground.name = "ground";
    ground.ground = true;
    g->bodies.push_back(ground);
    for (const auto& b : m.bodies) g->bodies.push_back({b.name, false, b.is_virtual, b.shapes});
    int first = 0;
    g->particle_attached.clear();
    for (const auto& flex : m.flex_bodies) {
      g->flex_bodies.push_back({flex->name(), first, flex->particle_count(), flex->grid_spacing()});
      first += flex->particle_count();
      const auto& ref = flex->reference_positions();
      for (int p = 0; p < flex->particle_count(); ++p) {
        g->reference_x.push_back(static_cast<float>(ref[2 * p]));
        g->reference_y.push_back(static_cast<float>(ref[2 * p + 1]));
        const BondStore& bonds = flex->bonds();
        g->bonds_initial.push_back(static_cast<uint16_t>(std::min<int64_t>(bonds.row[p + 1] - bonds.row[p], 65535)));
      }
      g->reference_xy.insert(g->reference_xy.end(), ref.begin(), ref.end());
      g->particle_volume.insert(g->particle_volume.end(), flex->volumes().begin(), flex->volumes().end());
    }
    g->particle_attached.assign(first, 0);
    g->particle_body.assign(first, 0);
    std::vector<int> coords;
    for (const auto& block : m.constraints) {
      if (block.origin != ConstraintBlock::Origin::kAttachment) continue;
      coords.clear();
      block.constraint->coordinates(coords);
      // the rigid body's coordinates come first (x, y, phi of rigid body c / 3: geometry index + 1)
      int holder = 0;
      for (int c : coords)
        if (c >= 0 && c < m.rigid_coordinates) holder = c / 3 + 1;
      for (int c : coords) {
        if (c < m.rigid_coordinates) continue;
        for (size_t f = 0; f < m.flex_bodies.size(); ++f) {
          const int off = m.flex_bodies[f]->coordinate_offset();
          if (c >= off && c < off + 2 * m.flex_bodies[f]->particle_count()) {
            g->particle_attached[g->flex_bodies[f].first_particle + (c - off) / 2] = 1;
            g->particle_body[g->flex_bodies[f].first_particle + (c - off) / 2] = holder;
          }
        }
      }
    }
    // bounds of the initial configuration
    Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
    auto grow = [&](const Vec2& p) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    };
    for (size_t k = 0; k < m.bodies.size(); ++k) grow(m.q0.segment<2>(3 * k));
    for (const auto& marker : m.markers) grow(marker.a.position(m.q0));
    for (int c = m.rigid_coordinates; c + 1 < m.coordinate_count; c += 2) grow(m.q0.segment<2>(c));
    if (lo.x() > hi.x()) lo = hi = Vec2::Zero();
    g->bounds_min = lo;
    g->bounds_max = hi;
    s.geometry = g;
  }
  out.geometry = s.geometry;
  out.time = s.time;
  out.step = s.steps;

  // rigid poses, ground first
  out.bodies.assign(1, Snapshot::Pose{});
  for (size_t k = 0; k < m.bodies.size(); ++k) {
    out.bodies.push_back({q[3 * k], q[3 * k + 1], q[3 * k + 2], qd[3 * k], qd[3 * k + 1], qd[3 * k + 2]});
  }
  fill_reactions(out);

  // particles
  out.px.clear();
  out.py.clear();
  out.damage.clear();
  out.displacement.clear();
  out.speed.clear();
  out.vx.clear();
  out.vy.clear();
  out.strain.clear();
  out.bonds_intact.clear();
  out.bond_pairs.clear();
  out.particle_q.clear();
  out.particle_qd.clear();
  std::vector<float> buffer;
  std::vector<std::pair<int, int>> pairs;
  out.max_damage = 0.0;
  int first = 0;
  for (const auto& flex : m.flex_bodies) {
    const int off = flex->coordinate_offset();
    const auto& ref = flex->reference_positions();
    for (int p = 0; p < flex->particle_count(); ++p) {
      const double x = q[off + 2 * p], y = q[off + 2 * p + 1];
      out.px.push_back(static_cast<float>(x));
      out.py.push_back(static_cast<float>(y));
      out.displacement.push_back(static_cast<float>(std::hypot(x - ref[2 * p], y - ref[2 * p + 1])));
      out.speed.push_back(static_cast<float>(std::hypot(qd[off + 2 * p], qd[off + 2 * p + 1])));
      out.vx.push_back(static_cast<float>(qd[off + 2 * p]));
      out.vy.push_back(static_cast<float>(qd[off + 2 * p + 1]));
    }
    if (out.full_precision) {
      out.particle_q.insert(out.particle_q.end(), q.data() + off, q.data() + off + 2 * flex->particle_count());
      out.particle_qd.insert(out.particle_qd.end(), qd.data() + off, qd.data() + off + 2 * flex->particle_count());
    }
    flex->damage(buffer);
    for (float d : buffer) out.max_damage = std::max(out.max_damage, static_cast<double>(d));
    out.damage.insert(out.damage.end(), buffer.begin(), buffer.end());
    flex->max_stretch(q, buffer);
    out.strain.insert(out.strain.end(), buffer.begin(), buffer.end());
    // intact bonds of each particle, for the window's inspector
    const BondStore& bonds = flex->bonds();
    const size_t at = out.bonds_intact.size();
    const int n = flex->particle_count();
    out.bonds_intact.resize(at + n);
    uint16_t* intact = out.bonds_intact.data() + at;
#pragma omp parallel for schedule(static) if (n >= 4096)
    for (int i = 0; i < n; ++i) {
      int64_t count = 0;
      for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) count += bonds.broken[k] ? 0 : 1;
      intact[i] = static_cast<uint16_t>(std::min<int64_t>(count, 65535));
    }
    if (flex->bond_count() < kDrawnBondLimit) {
      flex->bond_pairs(pairs, kDrawnBondLimit);
      for (const auto& [i, j] : pairs) out.bond_pairs.emplace_back(first + i, first + j);
    }
    first += flex->particle_count();
  }

  // joints, drivers, attachments, springs, probes
  out.markers.clear();
  for (const auto& marker : m.markers)
    out.markers.push_back({marker.kind, marker.a.position(q), marker.b.position(q), marker.a.body + 1, marker.b.body + 1});
  out.springs.clear();
  for (const auto& line : m.spring_lines) out.springs.push_back({line.a.position(q), line.b.position(q)});
  out.probes.clear();
  for (const auto& p : m.probes) {
    const Vec2 at = p.is_particle() ? Vec2(q[p.particle_coordinate], q[p.particle_coordinate + 1]) : p.point.position(q);
    out.probes.push_back({p.name, at, p.particle, p.is_particle() ? 0 : p.point.body + 1});
  }
  // active contacts (a pass of each contact of its own; nothing without [[contact]])
  s.contact_points.clear();
  for (const auto& contact : m.contacts) contact->collect_points(q, qd, s.contact_points);
  out.contacts.clear();
  for (const ContactPoint& c : s.contact_points) out.contacts.push_back({c.point, c.force});
  out.energies = s.energies();
  out.violation_position = s.dynamics->position_violation(s.time, q);
  out.violation_velocity = s.dynamics->velocity_violation(s.time, q, qd);
  out.broken_bonds = s.broken_bonds;
  // what the mouse holds: the anchor, the pull and its limits
  out.mouse = Snapshot::MouseGrip{};
  if (const auto& mouse = s.dynamics->mouse_spring()) {
    out.mouse.held = true;
    out.mouse.anchor = mouse->target_at(s.time);
    out.mouse.target = mouse->target;
    out.mouse.force = grip_force(*mouse, s.time, q);
    out.mouse.max_speed = mouse->speed;
    out.mouse.max_force = mouse->point.body >= 0 ? 0.0 : s.grip.max_force;
  }
}

LiveSettings Simulation::settings() const { return impl_->live; }

void Simulation::apply(const LiveSettings& settings) {
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

void Simulation::fill_reactions(Snapshot& out) const {
  Impl& s = *impl_;
  out.reactions.clear();
  if (!out.with_reactions || !s.dynamics->has_constraints()) return;
  // the multipliers at this very state (not at a trial stage of the last step)
  Eigen::VectorXd qdd;
  Eigen::Vector3d power;
  try {
    s.dynamics->derivative(s.time, s.state.q, s.state.qd, qdd, power);
  } catch (const NumericalError&) {
    return;
  }
  // each block's rows of -Phi_q^T lambda on the rigid coordinates it touches
  const int rigid = s.model->rigid_coordinates;
  Triplets jacobian;
  for (const auto& block : s.model->constraints) {
    if (block.origin == ConstraintBlock::Origin::kAttachment) continue;
    jacobian.clear();
    block.constraint->jacobian(s.state.q, s.time, 0, jacobian);
    const size_t first = out.reactions.size();
    for (const auto& e : jacobian) {
      if (e.col() >= rigid) continue;
      const int body = e.col() / 3 + 1;
      auto it = std::find_if(out.reactions.begin() + static_cast<std::ptrdiff_t>(first), out.reactions.end(),
                             [body](const Snapshot::Reaction& r) { return r.body == body; });
      if (it == out.reactions.end()) {
        out.reactions.push_back({block.constraint->name(), body, 0.0, 0.0, 0.0});
        it = out.reactions.end() - 1;
      }
      const double f = -e.value() * s.dynamics->row_multiplier(block.first_row + e.row());
      (e.col() % 3 == 0 ? it->fx : e.col() % 3 == 1 ? it->fy : it->moment) += f;
    }
  }
}

long Simulation::cut_bonds(const Vec2& a, const Vec2& b, const std::vector<float>& drawn_x,
                           const std::vector<float>& drawn_y) {
  Impl& s = *impl_;
  long cut = 0;
  size_t first = 0;
  std::vector<double> positions;
  for (auto& flex : s.model->flex_bodies) {
    // this body's particles as the caller shows them, when it gave every particle
    const size_t n = static_cast<size_t>(flex->particle_count());
    positions.clear();
    if (drawn_x.size() == drawn_y.size() && first + n <= drawn_x.size()) {
      for (size_t i = first; i < first + n; ++i) positions.insert(positions.end(), {drawn_x[i], drawn_y[i]});
    }
    first += n;
    const FractureUpdate update = flex->cut_bonds(s.state.q, positions, a, b);
    s.fracture_energy += update.energy_released;
    s.broken_bonds += update.bonds_broken;
    cut += update.bonds_broken;
    // the integrator's stored forces no longer hold
    if (update.forces_stale) s.integrator->reset();
  }
  return cut;
}

double Simulation::set_mouse_spring(const std::optional<MouseSpring>& spring) {
  Impl& s = *impl_;
  const SystemModel& m = *s.model;
  if (!spring) {
    s.dynamics->set_mouse_spring(std::nullopt);
    return 0.0;
  }
  // the same grab again: a drag moves the target only (no new patch, no integrator restart)
  std::optional<MouseSpringForce>& held = s.dynamics->mouse_spring();
  if (held && spring->stiffness <= 0.0 && held->grabbed_body == spring->body &&
      held->grabbed_particle == spring->particle) {
    // (an anchor waiting for the body keeps waiting: its walk resumes where it stands)
    held->from = held->target_at(s.time);
    held->since = std::max(held->since, s.time);
    held->target = spring->target;
    if (held->speed > 0.0) {
      // a hard grip (Shift) taken or let go during the drag
      const double factor = spring->hard == s.grip_hard ? 1.0 : spring->hard ? kHardGripFactor : 1.0 / kHardGripFactor;
      held->speed *= factor;
      s.grip.max_force *= factor;
      s.grip_hard = spring->hard;
    }
    return held->stiffness;
  }

  // How stiff: the held part follows the pointer at an angular frequency omega, so its
  // stiffness is (held mass) omega^2 and its damping 0.7 of critical, 1.4 (held mass) omega.
  // Explicit stepping stays stable with omega dt <= 0.3 and, for particles, with the bonds'
  // highest frequency (2 / critical step) and the spring's together under 2 / dt.
  const double dt = s.live.dt;
  double omega_stable = dt > 0.0 ? 0.3 / dt : 1e300;
  constexpr double kDampingRatio = 0.7;
  MouseSpringForce force;
  force.target = spring->target;
  force.grabbed_body = spring->body;
  force.grabbed_particle = spring->particle;
  if (spring->body >= 0 && spring->body < static_cast<int>(m.bodies.size())) {
    // a rigid body settles on the pointer within about a twentieth of the run (2 Hz over 10 s)
    const double end = s.scene.solver.end_time;
    const double omega = std::min(end > 0.0 ? 2.0 * kPi * 20.0 / end : 2.0 * kPi * 2.0, omega_stable);
    const double mass = m.bodies[spring->body].mass > 0.0 ? m.bodies[spring->body].mass : 1.0;
    force.point = BodyPoint{spring->body, spring->local_point};
    force.stiffness = spring->stiffness > 0.0 ? spring->stiffness : mass * omega * omega;
    force.damping = 2.0 * kDampingRatio * std::sqrt(force.stiffness * mass);
  } else if (spring->particle >= 0) {
    // snapshot order: the flexible bodies' particles concatenated
    int first = 0;
    for (const auto& flex : m.flex_bodies) {
      if (spring->particle >= first + flex->particle_count()) {
        first += flex->particle_count();
        continue;
      }
      // The patch within one horizon of the grabbed particle (as it lies now): one particle
      // alone is held back by its bonds and barely moves; a patch as wide as the bonds' reach
      // pulls the body as a finger would. It is held as stiffly as the step allows, since a
      // softer grip could not compete with the bonds around it and the body would not deform.
      const int offset = flex->coordinate_offset();
      const Eigen::VectorXd& q = s.state.q;
      const Vec2 grabbed(q[offset + 2 * (spring->particle - first)], q[offset + 2 * (spring->particle - first) + 1]);
      const double reach = flex->horizon();
      // the patch starts where it is and its anchor walks to the pointer at a speed the material
      // follows, pulling at most with the force the patch carries (mouse_grip.h): a pull, not
      // an impact, however fast the hand moved in the window's slow motion
      const auto def = std::find_if(s.scene.flex_bodies.begin(), s.scene.flex_bodies.end(),
                                    [&](const FlexBodyDef& d) { return d.name == flex->name(); });
      const double density = flex->volumes()[spring->particle - first] > 0.0
                                 ? flex->masses()[spring->particle - first] / flex->volumes()[spring->particle - first]
                                 : 0.0;
      if (def != s.scene.flex_bodies.end() && density > 0.0) {
        s.grip = grip_limits(def->material.youngs_modulus, density, flex->critical_stretch(), reach, def->thickness,
                             spring->hard);
      } else {
        s.grip = GripLimits{dt > 0.0 ? reach / (200.0 * dt) : 0.0, 0.0};
      }
      s.grip_hard = spring->hard;
      force.from = grabbed;
      force.since = s.time;
      force.speed = s.grip.max_speed;
      double omega = omega_stable;
      if (s.critical_step > 0.0 && dt > 0.0) {
        const double ratio = std::min(1.0, dt / s.critical_step);
        omega = std::min(omega, std::sqrt(1.0 - ratio * ratio) / dt);
      }
      const std::vector<double>& masses = flex->masses();
      for (int i = 0; i < flex->particle_count(); ++i) {
        const Vec2 p(q[offset + 2 * i], q[offset + 2 * i + 1]);
        if ((p - grabbed).squaredNorm() > reach * reach) continue;
        const double k = masses[i] * omega * omega;
        force.particle_coordinates.push_back(offset + 2 * i);
        force.offsets.push_back(p - grabbed);
        force.particle_stiffness.push_back(k);
        force.particle_damping.push_back(2.0 * kDampingRatio * masses[i] * omega);
        force.stiffness += k;
        force.damping += force.particle_damping.back();
      }
      if (spring->stiffness > 0.0 && force.stiffness > 0.0) {
        // a given total stiffness, shared in proportion to the masses
        const double scale = spring->stiffness / force.stiffness;
        for (double& k : force.particle_stiffness) k *= scale;
        for (double& c : force.particle_damping) c *= std::sqrt(scale);
        force.stiffness = spring->stiffness;
      }
      break;
    }
    if (force.particle_coordinates.empty()) return 0.0;
  } else {
    return 0.0;
  }
  s.dynamics->set_mouse_spring(force);
  s.integrator->reset();
  return force.stiffness;
}

}  // namespace periflex
