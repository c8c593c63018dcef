// What every contact model adds to a force element: the figures series.csv reports and the
// bound its stiffness puts on the explicit time step. Contacts live in SystemModel::contacts,
// apart from the other force elements, so a scene without [[contact]] never touches them.
#pragma once

#include <Eigen/Core>

#include "contact/contact_cache.h"
#include "mbs/force_element.h"
#include "scene/contact_def.h"

namespace periflex {

// Figures of one contact at a state.
struct ContactTotals {
  double normal_force = 0.0;  // sum of the normal force magnitudes over active contacts [N]
  long active = 0;            // particles (rigid_particles) or pairs (particles) in contact
};

class ContactElement : public ForceElement {
 public:
  // g += contact forces at (q, qd); returns the power they dissipate (add_forces and
  // dissipation_power in one pass over the particles, as the stepper needs both).
  virtual double add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                                        Eigen::VectorXd& g) = 0;
  // Active contacts and their normal forces at (q, qd).
  virtual ContactTotals totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) = 0;
  // Silling-Askari form sqrt(2 m / K) of the critical step of the particles this contact
  // touches, with the contact stiffness added to their bond stiffness (and its damping).
  virtual double critical_time_step() const = 0;
  // The same without the contact: the bound of the bonds alone.
  virtual double bond_critical_time_step() const = 0;
  // Penalty stiffness in use [N/m] (per particle or per pair), and the declaration.
  virtual double stiffness() const = 0;
  virtual const ContactDef& def() const = 0;
  // What the next evaluation reads from earlier ones (a Verlet list), for saving a state;
  // nothing for contacts that keep none.
  virtual void save_cache(ContactCache& out) const { out = ContactCache{}; }
  virtual void restore_cache(const ContactCache&) {}
};

// Damping ratio zeta of a linear spring-dashpot whose rebound keeps a fraction e of the
// approach speed: e = exp(-zeta pi / sqrt(1 - zeta^2)), so zeta = -ln e / sqrt(pi^2 + ln^2 e).
double damping_ratio(double restitution);

// Critical step of explicit central differences for an oscillator of undamped step h0 with
// damping ratio zeta: h0 (sqrt(1 + zeta^2) - zeta).
double damped_step(double undamped_step, double zeta);

}  // namespace periflex
