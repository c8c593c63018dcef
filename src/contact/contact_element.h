// What every contact model adds to a force element: the figures series.csv reports and the
// bound its stiffness puts on the explicit time step. Contacts live in SystemModel::contacts,
// apart from the other force elements, so a scene without [[contact]] never touches them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/contact_cache.h"
#include "core/vec2.h"
#include "mbs/force_element.h"
#include "scene/contact_def.h"

namespace periflex {

// Figures of one contact at a state.
struct ContactTotals {
  double normal_force = 0.0;  // sum of the normal force magnitudes over active contacts [N]
  long active = 0;            // particles (rigid_particles) or pairs (particles) in contact
};

// One active contact for drawing: where it acts and the force on its first side (the particle,
// the first particle of a pair, body_i) [N].
struct ContactPoint {
  Vec2 point = Vec2::Zero();
  Vec2 force = Vec2::Zero();
};

class ContactElement : public ForceElement {
 public:
  explicit ContactElement(const ContactDef& def) : def_(def) {}

  const std::string& name() const final { return def_.name; }
  // The declaration, and the penalty stiffness in use [N/m] (per particle, pair or shape pair).
  const ContactDef& def() const { return def_; }
  double stiffness() const { return stiffness_; }
  // The critical step of the bodies this contact touches without the contact: the bound of the
  // bonds alone (infinite between rigid bodies).
  double bond_critical_time_step() const { return bond_step_; }

  // g += contact forces at (q, qd); returns the power they dissipate (add_forces and
  // dissipation_power in one pass over the particles, as the stepper needs both).
  virtual double add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                                        Eigen::VectorXd& g) = 0;
  // Active contacts and their normal forces at (q, qd).
  virtual ContactTotals totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) = 0;
  // Silling-Askari form sqrt(2 m / K) of the critical step of the particles this contact
  // touches, with the contact stiffness added to their bond stiffness (and its damping).
  virtual double critical_time_step() const = 0;
  // What the next evaluation reads from earlier ones (a Verlet list), for saving a state;
  // nothing for contacts that keep none.
  virtual void save_cache(ContactCache& out) const { out = ContactCache{}; }
  virtual void restore_cache(const ContactCache&) {}
  // Appends the active contacts at (q, qd) to `out` (for the drawing; a pass of its own, on one
  // thread, only when a snapshot asks).
  virtual void collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                              std::vector<ContactPoint>& out) const = 0;

 protected:
  ContactDef def_;
  double stiffness_ = 0.0;  // set by each model's constructor
  double bond_step_ = 0.0;  // likewise
};

// Damping ratio zeta of a linear spring-dashpot whose rebound keeps a fraction e of the
// approach speed: e = exp(-zeta pi / sqrt(1 - zeta^2)), so zeta = -ln e / sqrt(pi^2 + ln^2 e).
double damping_ratio(double restitution);

// Critical step of explicit central differences for an oscillator of undamped step h0 with
// damping ratio zeta: h0 (sqrt(1 + zeta^2) - zeta).
double damped_step(double undamped_step, double zeta);

}  // namespace periflex
