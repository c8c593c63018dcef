// Breaking the bonds of a PdBody, whatever its law: the break pass once per accepted step, the
// breaks force evaluations made, the knife, and the broken bonds (with the law's own fields) as a
// saved state.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pd/pd_body_impl.h"

namespace periflex {

bool PdBody::breaks_in_evaluation() const { return impl_->breaks_in_evaluation(); }

FractureUpdate PdBody::take_evaluation_breaks() {
  Impl& m = *impl_;
  FractureUpdate update;
  update.bonds_broken = m.pending_broken;
  update.energy_released = m.pending_energy;
  m.pending_broken = 0;
  m.pending_energy = 0.0;
  return update;
}

FractureUpdate PdBody::update_fracture(const Eigen::VectorXd& q) {
  Impl& m = *impl_;
  // what the force evaluations since the last update broke (their forces are without them)
  FractureUpdate update = take_evaluation_breaks();
  if (!m.fracture || !std::isfinite(m.s0)) return update;
  // the law's break test, from the row maxima of the last force evaluation (which held every
  // bond) when it saw exactly these positions
  const bool cached = m.stretch_cache_valid &&
                      std::equal(m.stretch_cache_pos.begin(), m.stretch_cache_pos.end(), m.pos(q));
  m.stretch_cache_valid = false;
  const double* row_max = cached ? m.stretch_cache_most.data() : nullptr;
  const BreakResult broke = m.law->break_bonds(m.bonds, m.live, m.pos(q), m.no_fail_flags(), row_max);
  if (broke.pairs > 0) m.bonds_changed_on_host();
  m.broken_pairs += broke.pairs;
  update.bonds_broken += broke.pairs;
  update.energy_released += broke.energy;
  update.forces_stale = broke.pairs > 0;
  return update;
}

FractureUpdate PdBody::cut_bonds(const Eigen::VectorXd& q, const std::vector<double>& positions, const Vec2& a,
                                 const Vec2& b) {
  Impl& m = *impl_;
  FractureUpdate update;
  const double* p = positions.size() == 2 * static_cast<size_t>(m.n()) ? positions.data() : m.pos(q);
  const double before = potential_energy(q);
  // each pair once (i < j), both stored directions broken together
  const BondStore& bonds = m.bonds;
  BondState& live = m.live;
  std::vector<int> touched;
  for (int i = 0; i < m.n(); ++i) {
    const Vec2 pi(p[2 * i], p[2 * i + 1]);
    for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) {
      const int j = bonds.neighbor[k];
      if (j <= i || live.broken[k]) continue;
      if (!notch_cuts_bond(pi, Vec2(p[2 * j], p[2 * j + 1]), a, b, 1e-9 * m.dx * m.dx)) continue;
      live.break_bond(k);
      for (int64_t r = bonds.row[j]; r < bonds.row[j + 1]; ++r)
        if (bonds.neighbor[r] == i) live.break_bond(r);
      ++update.bonds_broken;
      if (touched.empty() || touched.back() != i) touched.push_back(i);
      touched.push_back(j);
    }
  }
  if (update.bonds_broken == 0) return update;
  m.law->bonds_cut(m.bonds, m.live, touched);
  m.bonds_changed_on_host();
  m.stretch_cache_valid = false;
  m.broken_pairs += update.bonds_broken;
  update.energy_released = before - potential_energy(q);
  update.forces_stale = true;
  return update;
}

void PdBody::save_state(FlexState& out) const {
  const Impl& m = *impl_;
  m.live.save_bits(out.broken_bits);
  out.broken_pairs = m.broken_pairs;
  out.pending_broken = m.pending_broken;
  out.pending_energy = m.pending_energy;
  // the law's own fields (none for the bond-based law)
  out.weighted_volume.clear();
  out.shear_coef.clear();
  out.bond_history.clear();
  m.law->save(out);
}

void PdBody::restore_state(const FlexState& in) {
  Impl& m = *impl_;
  const int64_t count = m.bonds.directed_count();
  if (in.broken_bits.size() != static_cast<size_t>((count + 63) / 64) || !m.law->state_fits(in, m.n(), count))
    throw std::invalid_argument("state of flexible body '" + m.def.name + "' does not match its bonds");
  m.live.restore_bits(m.bonds, in.broken_bits);
  m.broken_pairs = in.broken_pairs;
  m.pending_broken = in.pending_broken;
  m.pending_energy = in.pending_energy;
  m.law->restore(in);
  m.stretch_cache_valid = false;
  m.bonds_changed_on_host();
}

}  // namespace periflex
