#include "contact/rigid_particle_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_law.h"
#include "contact/contact_stiffness.h"
#include "contact/shape_distance.h"
#include "core/thread_pool.h"

namespace periflex {

namespace {
// Particles per chunk of the parallel pass.
constexpr int kShapeChunkParticles = 2048;
}  // namespace

RigidParticleContact::RigidParticleContact(const ContactDef& def, int body, double body_mass,
                                           std::vector<ShapeDef> shapes, const PdBody& flex,
                                           const std::vector<int>& excluded)
    : ContactElement(def),
      body_(body),
      body_mass_(body_mass),
      shapes_(std::move(shapes)),
      offset_(flex.coordinate_offset()),
      mass_(flex.masses()) {
  for (const ShapeDef& shape : shapes_) {
    Vec2 centre;
    double radius;
    bounding_circle(shape, centre, radius);
    bound_centre_.push_back(centre);
    bound_radius_.push_back(radius);
  }
  excluded_.assign(mass_.size(), 0);
  for (int i : excluded) excluded_[i] = 1;
  stiffness_ = def.stiffness > 0.0 ? def.stiffness : default_contact_stiffness(flex);
  margin_ = def.margin >= 0.0 ? def.margin : 0.5 * flex.grid_spacing();
  zeta_ = damping_ratio(def.restitution);
  bond_step_ = flex.critical_time_step();
  lightest_ = mass_.empty() ? 0.0 : *std::min_element(mass_.begin(), mass_.end());
}

RigidParticleContact::Sums RigidParticleContact::sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd,
                                                       Eigen::VectorXd* g, std::vector<ContactPoint>* points) const {
  const Vec2 r(q[3 * body_], q[3 * body_ + 1]);
  const double phi = q[3 * body_ + 2];
  const Mat2 a = rotation(phi), a_t = a.transpose();
  const Vec2 r_dot = qd ? Vec2((*qd)[3 * body_], (*qd)[3 * body_ + 1]) : Vec2::Zero();
  const double omega = qd ? (*qd)[3 * body_ + 2] : 0.0;
  const double k = stiffness_, mu = def_.friction, v_reg = def_.friction_velocity;

  const int n = static_cast<int>(mass_.size());
  const int chunks = (n + kShapeChunkParticles - 1) / kShapeChunkParticles;
  std::vector<Sums> partial(static_cast<size_t>(std::max(chunks, 1)));
  // one chunk's sweep, on the team's threads unless contact points are gathered (one list)
  const auto sweep_chunk = [&](int64_t chunk) {
    const int c = static_cast<int>(chunk);
    Sums& s = partial[c];
    const int end = std::min(n, (c + 1) * kShapeChunkParticles);
    for (int i = c * kShapeChunkParticles; i < end; ++i) {
      if (excluded_[i]) continue;
      const int x = offset_ + 2 * i;
      const Vec2 p(q[x], q[x + 1]);
      const Vec2 local = a_t * (p - r);
      // the deepest penetration over the body's shapes (bounding circles first)
      double depth = 0.0;
      Vec2 normal = Vec2::UnitX();
      for (size_t k_shape = 0; k_shape < shapes_.size(); ++k_shape) {
        if ((local - bound_centre_[k_shape]).squaredNorm() >
            (bound_radius_[k_shape] + margin_) * (bound_radius_[k_shape] + margin_))
          continue;
        const ShapeDistance d = signed_distance(shapes_[k_shape], local);
        if (margin_ - d.distance > depth) {
          depth = margin_ - d.distance;
          normal = a * d.normal;
        }
      }
      if (depth <= 0.0) continue;
      ++s.active;
      s.energy += 0.5 * k * depth * depth;

      // relative velocity of the particle and the body point it touches
      Vec2 v_rel = Vec2::Zero();
      if (qd) v_rel = Vec2((*qd)[x], (*qd)[x + 1]) - (r_dot + perp(p - r) * omega);
      const double m_eff = body_mass_ > 0.0 ? mass_[i] * body_mass_ / (mass_[i] + body_mass_) : mass_[i];
      const double damping = 2.0 * zeta_ * std::sqrt(k * m_eff);
      const ContactForce law = contact_force(k, damping, depth, normal, qd ? &v_rel : nullptr, mu, v_reg);
      s.normal_force += law.normal;
      s.dissipation += law.dissipation;
      const Vec2 force = law.force;
      if (g) {
        (*g)[x] += force.x();
        (*g)[x + 1] += force.y();
      }
      if (points) points->push_back({p, force});
      // the body gets -F at the particle
      s.fx -= force.x();
      s.fy -= force.y();
      s.moment -= cross(p - r, force);
    }
  };
  if (chunks > 1 && points == nullptr)
    parallel_for(chunks, sweep_chunk);
  else
    for (int c = 0; c < chunks; ++c) sweep_chunk(c);
  Sums total;
  for (const Sums& s : partial) {
    total.fx += s.fx;
    total.fy += s.fy;
    total.moment += s.moment;
    total.energy += s.energy;
    total.dissipation += s.dissipation;
    total.normal_force += s.normal_force;
    total.active += s.active;
  }
  if (g) {
    (*g)[3 * body_] += total.fx;
    (*g)[3 * body_ + 1] += total.fy;
    (*g)[3 * body_ + 2] += total.moment;
  }
  return total;
}

void RigidParticleContact::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double,
                                      Eigen::VectorXd& g) {
  sweep(q, &qd, &g);
}

double RigidParticleContact::add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double,
                                                   Eigen::VectorXd& g) {
  return sweep(q, &qd, &g).dissipation;
}

double RigidParticleContact::potential_energy(const Eigen::VectorXd& q) const {
  return sweep(q, nullptr, nullptr).energy;
}

double RigidParticleContact::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  if (zeta_ == 0.0 && def_.friction == 0.0) return 0.0;
  return sweep(q, &qd, nullptr).dissipation;
}

ContactTotals RigidParticleContact::totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const Sums s = sweep(q, &qd, nullptr);
  return {s.normal_force, s.active};
}

void RigidParticleContact::collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                          std::vector<ContactPoint>& out) const {
  sweep(q, &qd, nullptr, &out);
}

double RigidParticleContact::critical_time_step() const {
  // one contact per particle, on the lightest particle, added to its bond stiffness
  const double contact = damped_step(std::sqrt(2.0 * lightest_ / stiffness_), zeta_);
  const double bonds = bond_step_ > 0.0 && std::isfinite(bond_step_) ? 1.0 / (bond_step_ * bond_step_) : 0.0;
  return 1.0 / std::sqrt(bonds + 1.0 / (contact * contact));
}

bool RigidParticleContact::add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const {
  const Vec2 r(q[3 * body_], q[3 * body_ + 1]);
  const Mat2 a_t = rotation(q[3 * body_ + 2]).transpose();
  const std::vector<int> body = {3 * body_, 3 * body_ + 1, 3 * body_ + 2};
  pattern.add_block(body, body);
  std::vector<int> particle(2);
  for (size_t i = 0; i < mass_.size(); ++i) {
    if (excluded_[i]) continue;
    const int x = offset_ + 2 * static_cast<int>(i);
    const Vec2 local = a_t * (Vec2(q[x], q[x + 1]) - r);
    bool near = false;
    for (size_t k = 0; k < shapes_.size() && !near; ++k) {
      const double reach = bound_radius_[k] + 2.0 * margin_;
      near = (local - bound_centre_[k]).squaredNorm() <= reach * reach &&
             signed_distance(shapes_[k], local).distance < 2.0 * margin_;
    }
    if (!near) continue;
    particle = {x, x + 1};
    pattern.add_block(particle, particle);
    pattern.add_block(particle, body);
    pattern.add_block(body, particle);
  }
  return true;
}

}  // namespace periflex
