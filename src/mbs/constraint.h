// A block of constraint equations Phi(q, t) = 0 (Nikravesh, ch. 3-4).
// Joints, drivers, rigid-flexible attachments and prescribed particle motions all
// implement this; the solver assembles the blocks into one sparse Jacobian.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace periflex {

using Triplets = std::vector<Eigen::Triplet<double>>;

class Constraint {
 public:
  virtual ~Constraint() = default;

  virtual const std::string& name() const = 0;
  // Number of scalar equations in this block.
  virtual int rows() const = 0;
  // Rheonomic constraints (drivers) do work; the energy balance accounts for it.
  virtual bool is_driver() const { return false; }

  // Phi(q, t): writes rows() values.
  virtual void residual(const Eigen::VectorXd& q, double t, double* phi) const = 0;
  // Phi_q: appends triplets, equation k of this block on row row0 + k.
  virtual void jacobian(const Eigen::VectorXd& q, double t, int row0, Triplets& out) const = 0;
  // Phi_t; zero unless the constraint depends on time explicitly.
  virtual void time_derivative(const Eigen::VectorXd& q, double t, double* phi_t) const;
  // gamma = -(Phi_q qd)_q qd - 2 Phi_qt qd - Phi_tt: the right-hand side of Phi_q qdd = gamma.
  virtual void gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const = 0;
  // Indices of the coordinates the block depends on (with repeats allowed).
  virtual void coordinates(std::vector<int>& out) const = 0;
};

}  // namespace periflex
