// Contact between the shapes of two rigid bodies (penalty method, the law of rigid-particle
// contact). Each shape is touched through its feature points: a circle through its centre
// (radius r), a bar through its two end centres (radius its half-width), a box or polygon
// through its corners (radius 0). A feature point of one body's shape whose distance to the
// other body's shape is below its radius penetrates by d = r - distance and, at the point of
// its surface nearest the other shape, gets
//   F_n = max(0, k d + c d_dot) along the other shape's outward normal n,
//   F_t = -mu F_n v_t / max(|v_t|, v_reg)       (regularised Coulomb friction),
// with c = 2 zeta sqrt(k m_eff) from the coefficient of restitution, m_eff the reduced mass of
// the two bodies (a massless body, held by its joints, counts as infinitely heavy). The other
// body receives -F at the same point: forces and moments into both bodies' generalised forces,
// so momentum and angular momentum are exchanged exactly.
//
// Pairs: circle-anything is exact (the circle's centre against the other shape). Two convex
// polygonal shapes (box, convex polygon, bar) touch through their clipped contact manifold
// (contact/contact_manifold.h): up to two points on the face of least penetration, each with its
// own depth, found the same way for a corner's strike, a face resting on a face and two long
// shapes crossed deep in each other with no corner inside the other, so the law stays the
// gradient of one energy while the same features touch. A concave polygon touches through its
// corners against the other shape (one crossing it with no corner inside is not found).
#pragma once

#include <vector>

#include "contact/contact_element.h"
#include "scene/scene_def.h"

namespace periflex {

class RigidContact final : public ContactElement {
 public:
  // body_i, body_j: rigid body indices; their masses (0: held by joints) and body-fixed shapes.
  RigidContact(const ContactDef& def, int body_i, const BodyDef& def_i, int body_j, const BodyDef& def_j);

  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                                Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;

  ContactTotals totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  double critical_time_step() const override;
  void collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                      std::vector<ContactPoint>& out) const override;
  // The forces on both bodies move with both bodies' coordinates: the six are coupled whether
  // the shapes touch or not, so the pattern holds at any iterate.
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;

 private:
  // A point of a shape and the radius of its rounding, body-fixed.
  struct Feature {
    Vec2 point;
    double radius;
  };
  // One body's side: index, shapes, their feature points and bounding circles.
  struct Side {
    int body = 0;
    std::vector<ShapeDef> shapes;
    std::vector<std::vector<Feature>> features;  // per shape
    std::vector<Vec2> bound_centre;
    std::vector<double> bound_radius;
    // per shape: the convex core of the manifold, counter-clockwise, body-fixed, and its
    // rounding radius (empty: a circle or a concave polygon)
    std::vector<std::vector<Vec2>> core;
    std::vector<double> core_radius;
    bool round(size_t s) const { return shapes[s].kind == ShapeDef::Kind::kCircle; }
  };
  struct Sums {
    double energy = 0.0, dissipation = 0.0, normal_force = 0.0;
    long active = 0;
  };
  static Side make_side(int body, const BodyDef& def);
  // The features of shape `s` of `a` against shape `t` of `b`: forces into g when given.
  // The active contacts go into points when given (the force on a).
  void touch(const Side& a, size_t s, const Side& b, size_t t, const Eigen::VectorXd& q, const Eigen::VectorXd* qd,
             Eigen::VectorXd* g, std::vector<ContactPoint>* points, Sums& sums) const;
  // One contact: depth along n (out of b towards a) at c; the law's force +F on a, -F on b.
  void apply(int a, int b, const Vec2& c, const Vec2& n, double depth, const Eigen::VectorXd& q,
             const Eigen::VectorXd* qd, Eigen::VectorXd* g, std::vector<ContactPoint>* points, Sums& sums) const;
  // Shapes s of i and t of j, two convex cores: one contact per point of their manifold.
  void manifold(size_t s, size_t t, const Eigen::VectorXd& q, const Eigen::VectorXd* qd, Eigen::VectorXd* g,
                std::vector<ContactPoint>* points, Sums& sums) const;
  Sums sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, Eigen::VectorXd* g,
             std::vector<ContactPoint>* points = nullptr) const;

  Side i_, j_;
  double m_eff_ = 0.0, zeta_ = 0.0;
  double step_mass_ = 0.0;  // the mass a contact point feels, for the critical step
};

}  // namespace periflex
