#include "contact/rigid_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_law.h"
#include "contact/contact_manifold.h"
#include "contact/shape_distance.h"

namespace periflex {

namespace {

// The points through which a shape touches another, body-fixed, with their rounding radius.
std::vector<Vec2> corners(const ShapeDef& shape) {
  if (shape.kind == ShapeDef::Kind::kPolygon) return shape.vertices;
  const Mat2 a = rotation(shape.angle);
  const double w = 0.5 * shape.width, h = 0.5 * shape.height;
  return {shape.center + a * Vec2(-w, -h), shape.center + a * Vec2(w, -h), shape.center + a * Vec2(w, h),
          shape.center + a * Vec2(-w, h)};
}

// Reduced mass of two bodies; a massless body (held by its joints) counts as infinitely heavy.
double reduced_mass(double a, double b) {
  if (a <= 0.0) return b;
  if (b <= 0.0) return a;
  return a * b / (a + b);
}

}  // namespace

RigidContact::Side RigidContact::make_side(int body, const BodyDef& def) {
  Side side;
  side.body = body;
  side.shapes = def.shapes;
  for (const ShapeDef& shape : side.shapes) {
    std::vector<Feature> features;
    switch (shape.kind) {
      case ShapeDef::Kind::kCircle:
        features.push_back({shape.center, shape.radius});
        break;
      case ShapeDef::Kind::kBar:
        features.push_back({shape.p1, shape.radius});
        features.push_back({shape.p2, shape.radius});
        break;
      case ShapeDef::Kind::kBox:
      case ShapeDef::Kind::kPolygon:
        for (const Vec2& c : corners(shape)) features.push_back({c, 0.0});
        break;
      case ShapeDef::Kind::kNone:
      case ShapeDef::Kind::kBoolean:  // never a contact shape (flexible bodies and regions only)
        break;
    }
    // the convex core the manifold uses, with its rounding: a box's or convex polygon's corners;
    // a bar's end centres and its radius; none for a circle (its centre alone is exact) or a
    // concave polygon (its corners alone)
    std::vector<Vec2> core;
    double core_radius = 0.0;
    if (shape.kind == ShapeDef::Kind::kBox || shape.kind == ShapeDef::Kind::kPolygon) {
      for (const Feature& f : features) core.push_back(f.point);
      if (!is_convex(core)) core.clear();
    } else if (shape.kind == ShapeDef::Kind::kBar && shape.p2 != shape.p1) {
      core = {shape.p1, shape.p2};
      core_radius = shape.radius;
    }
    side.core.push_back(std::move(core));
    side.core_radius.push_back(core_radius);
    side.features.push_back(std::move(features));
    Vec2 centre;
    double radius;
    bounding_circle(shape, centre, radius);
    side.bound_centre.push_back(centre);
    side.bound_radius.push_back(radius);
  }
  return side;
}

RigidContact::RigidContact(const ContactDef& def, int body_i, const BodyDef& def_i, int body_j, const BodyDef& def_j)
    : ContactElement(def), i_(make_side(body_i, def_i)), j_(make_side(body_j, def_j)) {
  stiffness_ = def.stiffness;
  bond_step_ = std::numeric_limits<double>::infinity();  // no particles: nothing but the contact bounds the step
  zeta_ = damping_ratio(def.restitution);
  m_eff_ = reduced_mass(def_i.mass, def_j.mass);
  // the step: the mass a contact point feels at the far edge of each body, 1 / (1/m + rho^2 / I)
  // with rho the reach of its shapes from its centre (a long bar struck at its end is lighter
  // there than its mass), two contact points sharing a face
  const auto point_mass = [](const BodyDef& b, const Side& side) {
    if (b.mass <= 0.0) return 0.0;
    double reach = 0.0;
    for (size_t s = 0; s < side.shapes.size(); ++s)
      reach = std::max(reach, side.bound_centre[s].norm() + side.bound_radius[s]);
    return b.inertia > 0.0 ? 1.0 / (1.0 / b.mass + reach * reach / b.inertia) : b.mass;
  };
  step_mass_ = reduced_mass(point_mass(def_i, i_), point_mass(def_j, j_));
}

void RigidContact::touch(const Side& a, size_t s, const Side& b, size_t t, const Eigen::VectorXd& q,
                         const Eigen::VectorXd* qd, Eigen::VectorXd* g, std::vector<ContactPoint>* points,
                         Sums& sums) const {
  const Vec2 r_a(q[3 * a.body], q[3 * a.body + 1]), r_b(q[3 * b.body], q[3 * b.body + 1]);
  const Mat2 rot_a = rotation(q[3 * a.body + 2]), rot_b = rotation(q[3 * b.body + 2]);
  for (const Feature& feature : a.features[s]) {
    // the feature point in b's frame, its distance to b's shape
    const Vec2 x = r_a + rot_a * feature.point;
    const ShapeDistance d = signed_distance(b.shapes[t], rot_b.transpose() * (x - r_b));
    const double depth = feature.radius - d.distance;
    if (depth <= 0.0) continue;
    const Vec2 n = rot_b * d.normal;  // out of b, towards a
    // one point for both bodies: midway between a's surface and b's along n
    apply(a.body, b.body, x - (feature.radius - 0.5 * depth) * n, n, depth, q, qd, g, points, sums);
  }
}

void RigidContact::apply(int a, int b, const Vec2& c, const Vec2& n, double depth, const Eigen::VectorXd& q,
                         const Eigen::VectorXd* qd, Eigen::VectorXd* g, std::vector<ContactPoint>* points,
                         Sums& sums) const {
  const Vec2 r_a(q[3 * a], q[3 * a + 1]), r_b(q[3 * b], q[3 * b + 1]);
  const double k = stiffness_, mu = def_.friction, v_reg = def_.friction_velocity;
  const double damping = 2.0 * zeta_ * std::sqrt(k * m_eff_);
  ++sums.active;
  sums.energy += 0.5 * k * depth * depth;

  // velocity of a's point relative to b's point at c
  Vec2 v_rel = Vec2::Zero();
  if (qd) {
    const Vec2 v_a = Vec2((*qd)[3 * a], (*qd)[3 * a + 1]) + perp(c - r_a) * (*qd)[3 * a + 2];
    const Vec2 v_b = Vec2((*qd)[3 * b], (*qd)[3 * b + 1]) + perp(c - r_b) * (*qd)[3 * b + 2];
    v_rel = v_a - v_b;
  }
  const ContactForce law = contact_force(k, damping, depth, n, qd ? &v_rel : nullptr, mu, v_reg);
  sums.normal_force += law.normal;
  sums.dissipation += law.dissipation;
  const Vec2 force = law.force;
  if (g) {
    // +F on a, -F on b, both at c
    (*g)[3 * a] += force.x();
    (*g)[3 * a + 1] += force.y();
    (*g)[3 * a + 2] += cross(c - r_a, force);
    (*g)[3 * b] -= force.x();
    (*g)[3 * b + 1] -= force.y();
    (*g)[3 * b + 2] -= cross(c - r_b, force);
  }
  // drawn as the force on body_i
  if (points) points->push_back({c, a == i_.body ? force : Vec2(-force)});
}

void RigidContact::manifold(size_t s, size_t t, const Eigen::VectorXd& q, const Eigen::VectorXd* qd,
                            Eigen::VectorXd* g, std::vector<ContactPoint>* points, Sums& sums) const {
  // both shapes' cores where the bodies are now
  const auto world = [&](const Side& side, size_t shape) {
    const Vec2 r(q[3 * side.body], q[3 * side.body + 1]);
    const Mat2 rot = rotation(q[3 * side.body + 2]);
    std::vector<Vec2> out;
    for (const Vec2& p : side.core[shape]) out.push_back(r + rot * p);
    return out;
  };
  ContactManifold m;
  if (!convex_manifold(world(i_, s), i_.core_radius[s], world(j_, t), j_.core_radius[t], m)) return;
  for (int k = 0; k < m.count; ++k)
    apply(i_.body, j_.body, m.points[static_cast<size_t>(k)].point, m.normal, m.points[static_cast<size_t>(k)].depth,
          q, qd, g, points, sums);
}

RigidContact::Sums RigidContact::sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, Eigen::VectorXd* g,
                                       std::vector<ContactPoint>* points) const {
  Sums sums;
  const Vec2 r_i(q[3 * i_.body], q[3 * i_.body + 1]), r_j(q[3 * j_.body], q[3 * j_.body + 1]);
  const Mat2 rot_i = rotation(q[3 * i_.body + 2]), rot_j = rotation(q[3 * j_.body + 2]);
  for (size_t s = 0; s < i_.shapes.size(); ++s) {
    for (size_t t = 0; t < j_.shapes.size(); ++t) {
      // bounding circles first
      const Vec2 gap = (r_i + rot_i * i_.bound_centre[s]) - (r_j + rot_j * j_.bound_centre[t]);
      const double reach = i_.bound_radius[s] + j_.bound_radius[t];
      if (gap.squaredNorm() > reach * reach) continue;
      // a circle touches through its centre only; two convex shapes through their clipped
      // manifold, however deep; a concave polygon through its corners
      if (i_.round(s)) {
        touch(i_, s, j_, t, q, qd, g, points, sums);
      } else if (j_.round(t)) {
        touch(j_, t, i_, s, q, qd, g, points, sums);
      } else if (!i_.core[s].empty() && !j_.core[t].empty()) {
        manifold(s, t, q, qd, g, points, sums);
      } else {
        touch(i_, s, j_, t, q, qd, g, points, sums);
        touch(j_, t, i_, s, q, qd, g, points, sums);
      }
    }
  }
  return sums;
}

void RigidContact::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double, Eigen::VectorXd& g) {
  sweep(q, &qd, &g);
}

double RigidContact::add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double,
                                           Eigen::VectorXd& g) {
  return sweep(q, &qd, &g).dissipation;
}

double RigidContact::potential_energy(const Eigen::VectorXd& q) const { return sweep(q, nullptr, nullptr).energy; }

double RigidContact::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  if (zeta_ == 0.0 && def_.friction == 0.0) return 0.0;
  return sweep(q, &qd, nullptr).dissipation;
}

ContactTotals RigidContact::totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const Sums s = sweep(q, &qd, nullptr);
  return {s.normal_force, s.active};
}

void RigidContact::collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                  std::vector<ContactPoint>& out) const {
  sweep(q, &qd, nullptr, &out);
}

double RigidContact::critical_time_step() const {
  // two contact points on the lighter side's point mass: K = 2 k; no bound between massless bodies
  if (step_mass_ <= 0.0) return std::numeric_limits<double>::infinity();
  return damped_step(std::sqrt(2.0 * step_mass_ / stiffness_), zeta_);
}

bool RigidContact::add_coupling(const Eigen::VectorXd&, SparsityPattern& pattern) const {
  const std::vector<int> both = {3 * i_.body, 3 * i_.body + 1, 3 * i_.body + 2,
                                 3 * j_.body, 3 * j_.body + 1, 3 * j_.body + 2};
  pattern.add_block(both, both);
  return true;
}

}  // namespace periflex
