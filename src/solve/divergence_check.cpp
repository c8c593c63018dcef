// The divergence watch, after every step: a non-finite coordinate, constraint drift beyond a
// fraction of the model size, or energy far beyond what the model holds and was fed stops the
// run with a diagnostic that names the likely remedy.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel_chunks.h"

namespace periflex {

namespace {
using simulation_parts::kElasticCheckInterval;
using simulation_parts::number;
// Divergence bounds (documented in docs/solver.md): constraint violation above this fraction of
// the model size, kinetic energy above this multiple of the energy the model can hold.
constexpr double kViolationFraction = 0.05;
constexpr double kEnergyGrowth = 1e3;
}  // namespace

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

}  // namespace periflex
