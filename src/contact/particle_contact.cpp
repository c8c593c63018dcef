#include "contact/particle_contact.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact/contact_law.h"
#include "contact/contact_stiffness.h"
#include "core/thread_pool.h"

namespace periflex {

namespace {
// Particles per chunk of the parallel passes.
constexpr int kPairChunkParticles = 2048;
// Contacts assumed on the lightest particle for the critical step: about two neighbours across
// a contact face, each in relative motion (twice the stiffness of a fixed wall).
constexpr double kContactsPerParticle = 4.0;
}  // namespace

ParticleContact::ParticleContact(const ContactDef& def, const std::vector<const PdBody*>& bodies)
    : ContactElement(def), bodies_(bodies) {
  double spacing = 0.0, inverse_stiffness = 0.0;
  bond_step_ = 0.0;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    const PdBody& body = *bodies_[b];
    for (int i = 0; i < body.particle_count(); ++i) {
      coordinate_.push_back(body.coordinate_offset() + 2 * i);
      body_of_.push_back(static_cast<int>(b));
      local_.push_back(i);
      mass_.push_back(body.masses()[i]);
    }
    off_grid_.push_back(body.bonds().own_lengths() ? 1 : 0);
    spacing += body.grid_spacing() / static_cast<double>(bodies_.size());
    inverse_stiffness += 1.0 / default_contact_stiffness(body) / static_cast<double>(bodies_.size());
    const double step = body.critical_time_step();
    bond_step_ = b == 0 ? step : std::min(bond_step_, step);
  }
  // one law for every pair: the declared stiffness, else the harmonic mean of the bodies' defaults
  stiffness_ = def.stiffness > 0.0 ? def.stiffness : 1.0 / inverse_stiffness;
  distance_ = def.distance_ratio * spacing;
  distance_ratio_ = def.distance_ratio;
  skin_ = def.skin_ratio * spacing;
  zeta_ = damping_ratio(def.restitution);
  lightest_ = mass_.empty() ? 0.0 : *std::min_element(mass_.begin(), mass_.end());
}

void ParticleContact::save_cache(ContactCache& out) const {
  out.row = candidates_.row;
  out.col = candidates_.col;
  out.built_at = built_at_;
  out.built_broken = 0;  // no longer read: a broken bond needs no new search
}

void ParticleContact::restore_cache(const ContactCache& in) {
  const size_t n = coordinate_.size();
  const bool empty = in.row.empty() && in.col.empty() && in.built_at.empty();
  const bool sized = in.row.size() == n + 1 && in.built_at.size() == 2 * n &&
                     static_cast<int64_t>(in.col.size()) == in.row.back();
  bool inside = true;
  for (int32_t c : in.col) inside = inside && c >= 0 && static_cast<size_t>(c) < n;
  if (!empty && !(sized && inside))
    throw std::invalid_argument("state of contact '" + def_.name + "' does not match its particles");
  candidates_.row = in.row;
  candidates_.col = in.col;
  built_at_ = in.built_at;
  find_bonds();
}

int64_t ParticleContact::bond_between(int a, int b) const {
  if (body_of_[a] != body_of_[b]) return -1;
  // the copy in the row of the lower particle: both rows of the pair read the same flag
  const BondStore& bonds = bodies_[body_of_[a]]->bonds();
  const int i = std::min(local_[a], local_[b]), j = std::max(local_[a], local_[b]);
  for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) {
    if (bonds.neighbor[k] == j) return k;
  }
  return -1;
}

double ParticleContact::pair_distance(int a, int b, double d) const {
  if (!off_grid_[body_of_[a]] || body_of_[a] != body_of_[b]) return d;
  const std::vector<double>& x = bodies_[body_of_[a]]->reference_positions();
  const int i = local_[a], j = local_[b];
  return std::min(d, distance_ratio_ * std::hypot(x[2 * j] - x[2 * i], x[2 * j + 1] - x[2 * i + 1]));
}

void ParticleContact::find_bonds() const {
  const int n = static_cast<int>(coordinate_.size());
  candidate_bond_.assign(candidates_.col.size(), -1);
  candidate_distance_.clear();
  if (static_cast<int>(candidates_.row.size()) != n + 1) return;  // no list yet
  for (int a = 0; a < n; ++a) {
    for (int64_t e = candidates_.row[a]; e < candidates_.row[a + 1]; ++e)
      candidate_bond_[e] = bond_between(a, candidates_.col[e]);
  }
  // each pair's own contact distance, kept only where some body lies off the grid
  if (std::find(off_grid_.begin(), off_grid_.end(), 1) == off_grid_.end()) return;
  candidate_distance_.resize(candidates_.col.size());
  for (int a = 0; a < n; ++a) {
    for (int64_t e = candidates_.row[a]; e < candidates_.row[a + 1]; ++e)
      candidate_distance_[e] = pair_distance(a, candidates_.col[e], distance_);
  }
}

void ParticleContact::refresh(const Eigen::VectorXd& q) const {
  const int n = static_cast<int>(coordinate_.size());
  bool stale = static_cast<int>(built_at_.size()) != 2 * n;
  // a particle that moved half the skin may have a new partner within d
  const double limit2 = 0.25 * skin_ * skin_;
  for (int a = 0; a < n && !stale; ++a) {
    const double dx = q[coordinate_[a]] - built_at_[2 * a], dy = q[coordinate_[a] + 1] - built_at_[2 * a + 1];
    stale = dx * dx + dy * dy > limit2;
  }
  if (!stale) return;

  // every pair within d + skin, bonded or not, with the bond that joins it: a bond that breaks
  // later turns its pair into a contact pair without a new search
  x_.resize(n);
  y_.resize(n);
  built_at_.resize(2 * n);
  for (int a = 0; a < n; ++a) {
    x_[a] = built_at_[2 * a] = q[coordinate_[a]];
    y_[a] = built_at_[2 * a + 1] = q[coordinate_[a] + 1];
  }
  NeighborList all = find_neighbors(x_, y_, distance_ + skin_);
  candidates_.row = std::move(all.row);
  candidates_.col = std::move(all.col);
  find_bonds();
  ++rebuilds_;
}

ParticleContact::Sums ParticleContact::sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd,
                                             Eigen::VectorXd* g, std::vector<ContactPoint>* points) const {
  refresh(q);
  const int n = static_cast<int>(coordinate_.size());
  const int chunks = (n + kPairChunkParticles - 1) / kPairChunkParticles;
  const double k = stiffness_, d = distance_;
  std::vector<Sums> partial(static_cast<size_t>(std::max(chunks, 1)));
  // one chunk's sweep, on the team's threads unless contact points are gathered (one list)
  const auto sweep_chunk = [&](int64_t chunk) {
    const int c = static_cast<int>(chunk);
    Sums& s = partial[c];
    const int end = std::min(n, (c + 1) * kPairChunkParticles);
    for (int a = c * kPairChunkParticles; a < end; ++a) {
      const int xa = coordinate_[a];
      const uint8_t* broken = bodies_[body_of_[a]]->bond_state().broken.data();
      double fx = 0.0, fy = 0.0;
      for (int64_t e = candidates_.row[a]; e < candidates_.row[a + 1]; ++e) {
        // an intact bond holds the pair (a bond breaking mid-step is flagged 2: broken)
        const int64_t bond = candidate_bond_[e];
        if (bond >= 0 && broken[bond] == 0) continue;
        const int b = candidates_.col[e], xb = coordinate_[b];
        const double dx = q[xb] - q[xa], dy = q[xb + 1] - q[xa + 1];
        const double r2 = dx * dx + dy * dy;
        const double reach = candidate_distance_.empty() ? d : candidate_distance_[e];
        if (r2 >= reach * reach || r2 == 0.0) continue;
        const double r = std::sqrt(r2), overlap = reach - r;
        // out of b towards a; the velocity of a relative to b
        const Vec2 normal(-dx / r, -dy / r);
        Vec2 v_rel = Vec2::Zero();
        if (qd) v_rel = Vec2((*qd)[xa] - (*qd)[xb], (*qd)[xa + 1] - (*qd)[xb + 1]);
        const double m_eff = mass_[a] * mass_[b] / (mass_[a] + mass_[b]);
        const ContactForce law =
            contact_force(k, 2.0 * zeta_ * std::sqrt(k * m_eff), overlap, normal, qd ? &v_rel : nullptr);
        fx += law.force.x();
        fy += law.force.y();
        if (a < b) {
          ++s.active;
          s.energy += 0.5 * k * overlap * overlap;
          s.normal_force += law.normal;
          s.dissipation += law.dissipation;
          // midway between the two, the force on a
          if (points) points->push_back({Vec2(q[xa] + 0.5 * dx, q[xa + 1] + 0.5 * dy), law.force});
        }
      }
      if (g) {
        (*g)[xa] += fx;
        (*g)[xa + 1] += fy;
      }
    }
  };
  if (chunks > 1 && points == nullptr)
    parallel_for(chunks, sweep_chunk);
  else
    for (int c = 0; c < chunks; ++c) sweep_chunk(c);
  Sums total;
  for (const Sums& s : partial) {
    total.energy += s.energy;
    total.dissipation += s.dissipation;
    total.normal_force += s.normal_force;
    total.active += s.active;
  }
  return total;
}

void ParticleContact::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, Eigen::VectorXd& g) {
  sweep(q, &qd, &g);
}

double ParticleContact::add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double,
                                              Eigen::VectorXd& g) {
  return sweep(q, &qd, &g).dissipation;
}

double ParticleContact::potential_energy(const Eigen::VectorXd& q) const { return sweep(q, nullptr, nullptr).energy; }

double ParticleContact::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  if (zeta_ == 0.0) return 0.0;
  return sweep(q, &qd, nullptr).dissipation;
}

ContactTotals ParticleContact::totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const Sums s = sweep(q, &qd, nullptr);
  return {s.normal_force, s.active};
}

void ParticleContact::collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                     std::vector<ContactPoint>& out) const {
  sweep(q, &qd, nullptr, &out);
}

double ParticleContact::critical_time_step() const {
  const double contact = damped_step(std::sqrt(2.0 * lightest_ / (kContactsPerParticle * stiffness_)), zeta_);
  const double bonds = bond_step_ > 0.0 && std::isfinite(bond_step_) ? 1.0 / (bond_step_ * bond_step_) : 0.0;
  return 1.0 / std::sqrt(bonds + 1.0 / (contact * contact));
}

bool ParticleContact::add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const {
  refresh(q);
  for (size_t a = 0; a < coordinate_.size(); ++a) {
    const int xa = coordinate_[a];
    for (int64_t e = candidates_.row[a]; e < candidates_.row[a + 1]; ++e) {
      const int xb = coordinate_[candidates_.col[e]];
      // the pair force on a moves with both coordinates of a and of b
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          pattern.add(xa + r, xa + c);
          pattern.add(xa + r, xb + c);
        }
    }
  }
  return true;
}

}  // namespace periflex
