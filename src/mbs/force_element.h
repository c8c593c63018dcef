// Anything that adds generalised forces to g: springs, dampers, actuators, applied loads,
// and the peridynamic bond forces of a flexible body. Each reports the energies it stores,
// dissipates or feeds in, so the run can check its energy balance.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/sparsity_pattern.h"

namespace periflex {

class ForceElement {
 public:
  virtual ~ForceElement() = default;
  virtual const std::string& name() const = 0;

  // g += Q(q, qd, t).
  virtual void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                          Eigen::VectorXd& g) = 0;
  // Stored (potential / strain) energy at q.
  virtual double potential_energy(const Eigen::VectorXd& q) const { return 0.0; }
  // Power removed by damping at (q, qd), >= 0.
  virtual double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const { return 0.0; }
  // Power fed in by actuators and applied loads that are not in potential_energy.
  virtual double external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const {
    return 0.0;
  }
  // Adds the pairs (row, column) of g whose forces move when q or qd of the column moves, at
  // the state q (a superset is fine; the diagonal is implied). False when the element cannot
  // tell, and an implicit integrator then finds the pattern by perturbing every coordinate.
  virtual bool add_coupling(const Eigen::VectorXd& /*q*/, SparsityPattern& /*pattern*/) const { return false; }
};

}  // namespace periflex
