#include "pd/bilinear_softening_law.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_chunks.h"
#include "pd/bond_based_law.h"
#include "pd/pd_material.h"
#include "pd/row_blocks.h"

// The bond loops of this law are portable (no hand-written vector rows): rows in fixed blocks
// (row_blocks.h), so results do not depend on the thread count.

namespace periflex {

SofteningStretches softening_stretches(double g0, double ratio, double s0, double e, double delta,
                                       bool plane_strain, FlexBodyDef::Influence kind) {
  // the brittle law's s0 makes the triangle of the same area: s0 s1 / 2 = sc^2 / 2
  const double sc = critical_stretch_from_energy(g0, e, delta, plane_strain, kind);
  SofteningStretches curve;
  if (s0 > 0.0) {
    curve.s0 = s0;
    curve.s1 = sc * sc / s0;
  } else {
    curve.s0 = sc / std::sqrt(ratio);
    curve.s1 = sc * std::sqrt(ratio);
  }
  return curve;
}

double softening_bond_energy(double s, double h, const SofteningStretches& c) {
  const double m = std::max(h, s);
  if (s <= 0.0 || m <= c.s0) return 0.5 * s * s;
  // force f / k on the falling branch at stretch x, and its integral from a to b
  const double slope = c.s0 / (c.s1 - c.s0);
  auto envelope = [&](double x) { return slope * (c.s1 - x); };
  auto area = [&](double a, double b) { return slope * (c.s1 * (b - a) - 0.5 * (b * b - a * a)); };
  if (h >= c.s1) return 0.0;  // broken
  // unloading (s <= h): on the secant of slope omega(h) = envelope(h) / h
  if (s <= h) return 0.5 * envelope(h) / h * s * s;
  // loading past h and s0: the energy at the start of the branch, then along it (flat past s1)
  const double start = h <= c.s0 ? c.s0 : h;
  const double base = 0.5 * envelope(start) * start;
  return base + area(start, std::min(s, c.s1));
}

BilinearSofteningLaw::BilinearSofteningLaw(const FlexBodyDef& def, double horizon, std::vector<std::string>&) {
  const PdMaterialDef& mat = def.material;
  require_material(def, mat.fracture_energy > 0.0, "fracture_energy",
                   "model = \"bilinear_softening\" needs fracture_energy (the area under its curve)");
  require_material(def, mat.softening_ratio > 1.0 || mat.critical_stretch > 0.0, "softening_ratio",
                   "model = \"bilinear_softening\" needs softening_ratio (s1 / s0, above 1) or critical_stretch (s0)");
  curve_ = softening_stretches(mat.fracture_energy, mat.softening_ratio, mat.critical_stretch, mat.youngs_modulus,
                               horizon, mat.plane_strain, def.influence);
  require_material(def, curve_.s1 > curve_.s0, "critical_stretch",
                   "critical_stretch must lie below the brittle critical stretch of this fracture_energy (" +
                       std::to_string(std::sqrt(curve_.s0 * curve_.s1)) +
                       "), or the softening branch would rise");
}

void BilinearSofteningLaw::set_coefficients(const LawSetup& setup, BondStore& bonds) {
  set_bond_stiffness(setup, bonds);
  history_.assign(bonds.neighbor.size(), 0.0);
  linear_.assign(bonds.neighbor.size(), 0);
  if (!setup.no_fail) return;
  for (int i = 0; i < bonds.particle_count(); ++i)
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
      linear_[b] = setup.no_fail[i] || setup.no_fail[bonds.neighbor[b]];
}

double BilinearSofteningLaw::critical_time_step(const BondStore& bonds, const BondState& live,
                                                const std::vector<double>& masses) const {
  // softening only lowers the stiffness: the bound of the intact springs holds
  return spring_critical_time_step(bonds, live, masses);
}

double BilinearSofteningLaw::secant_factor(double s, double h) const {
  const double m = std::max(h, s);
  if (s <= 0.0 || m <= curve_.s0) return 1.0;
  if (m >= curve_.s1) return 0.0;
  return curve_.s0 * (curve_.s1 - m) / (m * (curve_.s1 - curve_.s0));
}

void BilinearSofteningLaw::add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) {
  const double* pos = e.pos;
  const double* vel = e.eta_over_e > 0.0 ? e.vel : nullptr;
  for_row_blocks(bonds.particle_count(), [&](int begin, int end) {
    if (e.pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, e.pos_copy + 2 * begin);
    for (int i = begin; i < end; ++i) {
      double fx = 0.0, fy = 0.0, top = -1.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const double k = live.stiffness[b];
        if (k == 0.0) continue;  // broken
        const int32_t j = bonds.neighbor[b];
        const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
        const double len = std::sqrt(dx * dx + dy * dy), l0 = bonds.inv_length(b);
        const double s = len * l0 - 1.0;
        top = std::max(top, s);
        const double omega = linear_[b] ? 1.0 : secant_factor(s, history_[b]);
        // k omega s along y / |y|, plus the damping k omega eta/E ds/dt
        double f = k * omega * (l0 - 1.0 / len);
        if (vel) {
          const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
          f += k * omega * e.eta_over_e * ((dx * dvx + dy * dvy) / len * l0) / len;
        }
        fx += f * dx;
        fy += f * dy;
      }
      if (e.row_max) e.row_max[i] = top;
      e.force[2 * i] += fx;
      e.force[2 * i + 1] += fy;
    }
  });
}

double BilinearSofteningLaw::strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const {
  // half of the pair's k |xi| psi(s; h) per stored direction, rows in fixed ranges added in order
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int i = static_cast<int>(begin); i < static_cast<int>(end); ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const double k = live.stiffness[b];
        if (k == 0.0) continue;
        const int32_t j = bonds.neighbor[b];
        const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
        const double l0 = bonds.inv_length(b);
        const double s = std::sqrt(dx * dx + dy * dy) * l0 - 1.0;
        const double psi = linear_[b] ? 0.5 * s * s : softening_bond_energy(s, history_[b], curve_);
        sum += 0.5 * k * psi / l0;
      }
    }
    return sum;
  });
}

double BilinearSofteningLaw::damping_power(const BondStore& bonds, const BondState& live, const double* pos,
                                           const double* vel, double eta_over_e) const {
  // k omega eta/E |xi| (ds/dt)^2 per pair, half per stored direction
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int i = static_cast<int>(begin); i < static_cast<int>(end); ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const double k = live.stiffness[b];
        if (k == 0.0) continue;
        const int32_t j = bonds.neighbor[b];
        const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
        const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
        const double l0 = bonds.inv_length(b), len = std::sqrt(dx * dx + dy * dy);
        const double omega = linear_[b] ? 1.0 : secant_factor(len * l0 - 1.0, history_[b]);
        const double rate = (dx * dvx + dy * dvy) / len * l0;
        sum += 0.5 * k * omega * eta_over_e * rate * rate / l0;
      }
    }
    return sum;
  });
}

void BilinearSofteningLaw::energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                                          const std::vector<double>& volumes, double* out) const {
  for (int i = 0; i < bonds.particle_count(); ++i) {
    double sum = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const double k = live.stiffness[b];
      if (k == 0.0) continue;
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double l0 = bonds.inv_length(b);
      const double s = std::sqrt(dx * dx + dy * dy) * l0 - 1.0;
      sum += 0.5 * k * (linear_[b] ? 0.5 * s * s : softening_bond_energy(s, history_[b], curve_)) / l0;
    }
    out[i] = sum / volumes[i];
  }
}

BreakResult BilinearSofteningLaw::break_bonds(const BondStore& bonds, BondState& live, const double* pos,
                                              const uint8_t*, const double* row_max) {
  // in row order on one thread: the same sum on any thread count. Only rows whose largest
  // stretch passed s0 can raise a history (the force evaluation's maxima when it saw these positions).
  BreakResult result;
  long directed = 0;
  const int n = bonds.particle_count();
  for (int i = 0; i < n; ++i) {
    if (row_max && row_max[i] <= curve_.s0) continue;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (live.broken[b] || linear_[b]) continue;
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double l0 = bonds.inv_length(b);
      const double s = std::sqrt(dx * dx + dy * dy) * l0 - 1.0;
      const double h = history_[b];
      if (s <= curve_.s0 || s <= h) continue;
      // what raising h to s takes out of the bond: its energy at s before minus after
      const double k = live.stiffness[b];
      result.energy += 0.5 * k * (softening_bond_energy(s, h, curve_) - softening_bond_energy(s, s, curve_)) / l0;
      history_[b] = s;
      if (s < curve_.s1) continue;
      live.break_bond(b);
      ++directed;
    }
  }
  result.pairs = directed / 2;
  return result;
}

bool BilinearSofteningLaw::state_fits(const FlexState& in, int, int64_t directed) const {
  return in.bond_history.size() == static_cast<size_t>(directed);
}

size_t BilinearSofteningLaw::memory_bytes() const {
  return history_.capacity() * sizeof(double) + linear_.capacity();
}

}  // namespace periflex
