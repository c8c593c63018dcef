// Per-particle fields of a PdBody for drawing, output and diagnostics (damage, largest stretch,
// strain energy density, memory), and the queries that find particles by place.
#include <algorithm>
#include <limits>

#include "core/parallel_chunks.h"
#include "pd/pd_body_impl.h"

namespace periflex {

void PdBody::damage(std::vector<float>& out) const {
  const Impl& m = *impl_;
  const BondStore& b = m.bonds;
  out.resize(m.n());
  // 1 - intact weight / initial weight, the weight of a bond being its partial-volume factor
  const int n = m.n();
  const uint8_t* broken = m.live.broken.data();
  // the weight of stored direction k: its own off the grid, its length class's on it (the choice
  // made once, not per bond: this runs for every series row and frame)
  const auto rows = [&](int64_t begin, int64_t end, auto weight_of) {
    for (int64_t i = begin; i < end; ++i) {
      double intact = 0.0;
      for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) intact += broken[k] ? 0.0 : weight_of(k);
      const double d = m.initial_weight[i] > 0.0 ? 1.0 - intact / m.initial_weight[i] : 0.0;
      out[i] = static_cast<float>(std::clamp(d, 0.0, 1.0));
    }
  };
  const double* own = m.bond_weight.data();
  const double* by_class = m.class_weight.data();
  const uint8_t* cls = b.length_class.data();
  parallel_chunks(n, [&](int64_t, int64_t begin, int64_t end) {
    if (b.own_lengths())
      rows(begin, end, [own](int64_t k) { return own[k]; });
    else
      rows(begin, end, [by_class, cls](int64_t k) { return by_class[cls[k]]; });
  });
}

void PdBody::max_stretch(const Eigen::VectorXd& q, std::vector<float>& out) const {
  out.resize(impl_->n());
  max_bond_stretch(impl_->bonds, impl_->live, impl_->pos(q), out.data());
}

void PdBody::strain_energy_density(const Eigen::VectorXd& q, std::vector<double>& out) const {
  const Impl& m = *impl_;
  out.resize(m.n());
  m.law->energy_density(m.bonds, m.live, m.pos(q), m.volume, out.data());
}

size_t PdBody::memory_bytes() const {
  const Impl& m = *impl_;
  const size_t per_particle_doubles = m.reference.capacity() + m.mass.capacity() + m.volume.capacity() +
                                      m.grid.x.capacity() + m.grid.y.capacity() + m.initial_weight.capacity() +
                                      m.stretch_cache_pos.capacity() + m.stretch_cache_most.capacity();
  const size_t per_particle_bytes = m.no_fail.capacity() + m.row_broke.capacity();
  return m.bonds.bytes() + m.live.bytes() + per_particle_doubles * sizeof(double) +
         (m.grid.ix.capacity() + m.grid.iy.capacity()) * sizeof(int32_t) + per_particle_bytes +
         m.law->memory_bytes();
}

int PdBody::nearest_particle(const Vec2& point) const {
  const Impl& m = *impl_;
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.n(); ++i) {
    const double dx = m.grid.x[i] - point.x(), dy = m.grid.y[i] - point.y();
    const double d2 = dx * dx + dy * dy;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

std::vector<int> PdBody::particles_in(const ShapeDef& region) const {
  const Impl& m = *impl_;
  std::vector<int> out;
  for (int i = 0; i < m.n(); ++i)
    if (region.contains(Vec2(m.grid.x[i], m.grid.y[i]))) out.push_back(i);
  return out;
}

void PdBody::bond_pairs(std::vector<std::pair<int, int>>& out, size_t max_pairs) const {
  const BondStore& b = impl_->bonds;
  const std::vector<uint8_t>& broken = impl_->live.broken;
  out.clear();
  for (int i = 0; i < b.particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      if (broken[k] || b.neighbor[k] <= i) continue;
      if (out.size() >= max_pairs) {
        out.clear();
        return;
      }
      out.emplace_back(i, b.neighbor[k]);
    }
  }
}

}  // namespace periflex
