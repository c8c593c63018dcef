// Contact of a rigid body's shapes with the particles of a flexible body (penalty method).
// A particle nearer the shape than `margin` (half the grid spacing by default: a particle is
// the centre of a cell of that half-width) penetrates by d = margin - distance, and gets
//   F_n = max(0, k d + c d_dot) along the shape's outward normal n,
//   F_t = -mu F_n v_t / max(|v_t|, v_reg)       (regularised Coulomb friction),
// with c = 2 zeta sqrt(k m_eff) from the coefficient of restitution. The rigid body receives
// -F at the particle's position (force and moment about its origin), so the momentum the two
// exchange balances exactly. The energy k d^2 / 2 is stored; the damping and friction power
// is dissipated (docs/contact.md).
#pragma once

#include <string>
#include <vector>

#include "contact/contact_element.h"
#include "pd/pd_body.h"

namespace periflex {

class RigidParticleContact final : public ContactElement {
 public:
  // body: rigid body index (coordinates 3 body .. 3 body + 2), body_mass its mass (0: virtual);
  // shapes: its body-fixed drawing shapes; excluded: particle indices of the flexible body that
  // never touch it (attached to it).
  RigidParticleContact(const ContactDef& def, int body, double body_mass, std::vector<ShapeDef> shapes,
                       const PdBody& flex, const std::vector<int>& excluded);

  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                                Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;

  ContactTotals totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  double critical_time_step() const override;
  void collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                      std::vector<ContactPoint>& out) const override;
  // The body's coordinates with those of every particle nearer a shape than twice the margin:
  // the particles in contact, and those a Newton iterate may bring into it within a step (the
  // pattern is taken again at each new tangent). Every such particle's columns share the body's
  // rows, so each takes a colour of its own: the band is kept to one margin.
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;

 private:
  // What one pass over the particles adds up.
  struct Sums {
    double fx = 0.0, fy = 0.0, moment = 0.0;  // on the rigid body
    double energy = 0.0, dissipation = 0.0, normal_force = 0.0;
    long active = 0;
  };
  // One pass at q (and qd when given): particle forces into g when given, the active contacts
  // into points when given (then on one thread), and the sums. Fixed chunks of particles,
  // partial sums added in chunk order: the same bits on any thread count.
  Sums sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, Eigen::VectorXd* g,
             std::vector<ContactPoint>* points = nullptr) const;

  int body_;
  double body_mass_;
  std::vector<ShapeDef> shapes_;
  std::vector<Vec2> bound_centre_;
  std::vector<double> bound_radius_;
  int offset_;                    // q index of the first particle's x
  std::vector<double> mass_;      // per particle
  std::vector<char> excluded_;    // per particle
  double margin_, zeta_;
  double lightest_ = 0.0;
};

}  // namespace periflex
