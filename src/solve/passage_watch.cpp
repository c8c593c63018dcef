// The passage watch (rank monitoring): a passage through a singular position must leave the
// energy balance where it was; a jump says the motion may have switched branch, and the run stops
// naming the dependent constraints.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace periflex {

namespace {
using simulation_parts::kElasticCheckInterval;
using simulation_parts::number;
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

}  // namespace periflex
