// The equations of motion: the accelerations of the constrained system at (t, q, qd), forces
// and the constraint solve (the rows that stay: dynamics_rows.cpp; projections onto the
// constraints: dynamics_projection.cpp).
#include "solve/dynamics.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "solve/held_rotations.h"

namespace periflex {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }
}  // namespace

double MouseSpringForce::stored_energy(double t, const Eigen::VectorXd& q) const {
  const Vec2 aim = target_at(t);
  double energy = 0.0;
  if (point.body >= 0) energy += 0.5 * stiffness * (aim - point.position(q)).squaredNorm();
  for (size_t k = 0; k < particle_coordinates.size(); ++k) {
    const int c = particle_coordinates[k];
    energy += 0.5 * particle_stiffness[k] * (aim + offsets[k] - Vec2(q[c], q[c + 1])).squaredNorm();
  }
  return energy;
}

Dynamics::Dynamics(SystemModel& model) : model_(model) {}

void Dynamics::assemble_jacobian(double t, const Eigen::VectorXd& q) {
  all_.clear();
  for (const auto& block : model_.constraints) block.constraint->jacobian(q, t, block.first_row, all_);
  local_j_.clear();
  prescribed_j_.clear();
  for (const auto& e : all_) {
    const int row = active_index_[e.row()];
    if (row < 0) continue;
    const int col = local_[e.col()];
    if (col >= 0) {
      local_j_.emplace_back(row, col, e.value());
    } else if (model_.is_prescribed[e.col()]) {
      prescribed_j_.emplace_back(row, e.col(), e.value());
    }
  }
}

void Dynamics::residual_all(double t, const Eigen::VectorXd& q) {
  phi_all_.resize(model_.constraint_rows);
  for (const auto& block : model_.constraints) block.constraint->residual(q, t, phi_all_.data() + block.first_row);
}

void Dynamics::time_derivative_all(double t, const Eigen::VectorXd& q) {
  phi_t_all_.resize(model_.constraint_rows);
  for (const auto& block : model_.constraints) {
    block.constraint->time_derivative(q, t, phi_t_all_.data() + block.first_row);
  }
}

void Dynamics::assemble_reduced(double t, const Eigen::VectorXd& q) {
  // active row -> reduced row, rebuilt from reduced_rows_ (cheap next to the triplets)
  std::vector<int>& row_of = active_index_work_;
  row_of.assign(active_.size(), -1);
  for (size_t r = 0; r < reduced_rows_.size(); ++r) row_of[reduced_rows_[r]] = static_cast<int>(r);
  all_.clear();
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    if (condensed_.block_condensed(k)) continue;
    const ConstraintBlock& block = model_.constraints[k];
    block.constraint->jacobian(q, t, block.first_row, all_);
  }
  reduced_j_.clear();
  prescribed_j_.clear();
  for (const auto& e : all_) {
    const int active = active_index_[e.row()];
    if (active < 0) continue;
    const int row = row_of[active];
    if (row < 0) continue;  // an eliminated particle's row of a joint kept in part
    const int col = reduced_col_[e.col()];
    if (col >= 0) {
      reduced_j_.emplace_back(row, col, e.value());
    } else if (model_.is_prescribed[e.col()]) {
      prescribed_j_.emplace_back(row, e.col(), e.value());
    }
  }
  condensed_.update(q);
}

void Dynamics::velocity_residual_all(const Eigen::VectorXd& qd) {
  nu_all_ = phi_t_all_;
  for (const auto& e : reduced_j_) nu_all_[active_[reduced_rows_[e.row()]]] += e.value() * qd[reduced_cols_[e.col()]];
  for (const auto& e : prescribed_j_) nu_all_[active_[reduced_rows_[e.row()]]] += e.value() * qd[e.col()];
  condensed_.velocity_residual(qd, nu_all_.data());
}

bool Dynamics::solve_dense(const Eigen::VectorXd& w, const double* a, const double* e,
                           DenseConstraintSolver& solver, Eigen::VectorXd& z) {
  // every row is active and reduced (no eliminated joints), so reduced row r is global row r
  const int nr = static_cast<int>(reduced_cols_.size()), mr = static_cast<int>(reduced_rows_.size());
  Eigen::MatrixXd& j = solver.jacobian();
  j.setZero();
  for (const auto& t : reduced_j_) j(t.row(), t.col()) += t.value();
  diag_.resize(nr);
  select_.resize(nr);
  rhs_.resize(nr + mr);
  for (int k = 0; k < nr; ++k) {
    diag_[k] = w[reduced_cols_[k]];
    select_[k] = selection_[reduced_cols_[k]];
    rhs_[k] = a ? a[reduced_cols_[k]] : 0.0;
  }
  for (int r = 0; r < mr; ++r) rhs_[nr + r] = e[active_[reduced_rows_[r]]];
  if (!solver.factorize(diag_.data(), select_.data(), kRankThreshold)) return false;
  x_.resize(nr + mr);
  solver.solve(rhs_.data(), rhs_.data() + nr, x_.data(), x_.data() + nr);
  if (!x_.allFinite()) return false;
  for (int k = 0; k < nr; ++k) z[reduced_cols_[k]] = x_[k];
  return true;
}

bool Dynamics::solve_constrained(const Eigen::VectorXd& w, const double* a, const double* e, KktSolver& solver,
                                 Eigen::VectorXd& z) {
  if (dense_) {
    return solve_dense(w, a, e, &solver == &kkt_ ? dense_acceleration_ : dense_projection_, z);
  }
  const int nr = static_cast<int>(reduced_cols_.size()), mr = static_cast<int>(reduced_rows_.size());
  diag_.resize(nr);
  rhs_.resize(nr + mr);
  for (int k = 0; k < nr; ++k) {
    diag_[k] = w[reduced_cols_[k]];
    rhs_[k] = a ? a[reduced_cols_[k]] : 0.0;
  }
  for (int r = 0; r < mr; ++r) rhs_[nr + r] = e[active_[reduced_rows_[r]]];
  coupling_.clear();
  if (!condensed_.empty()) {
    condensed_.add_body_blocks(w, reduced_col_, diag_, coupling_);
    condensed_.add_body_rhs(a, w, e, reduced_col_, rhs_);
  }
  if (nr > 0) {
    if (!solver.factorize(diag_, reduced_j_, mr, &coupling_)) return false;
    x_ = solver.solve(rhs_);
    if (!x_.allFinite()) return false;
    for (int k = 0; k < nr; ++k) z[reduced_cols_[k]] = x_[k];
  }
  condensed_.recover(e, z);
  return true;
}

void Dynamics::throw_singular(double t, const Eigen::VectorXd& q, const std::string& during) {
  // find the blocks whose rows became dependent, to name them
  assemble_jacobian(t, q);
  Eigen::SparseMatrix<double> j(active_rows(), constrained_coordinates());
  j.setFromTriplets(local_j_.begin(), local_j_.end());
  std::string names;
  for (int a : dependent_active_rows(j, 1e-8)) {
    const std::string& name = block_of_row(active_[a]);
    if (names.find("'" + name + "'") == std::string::npos) names += (names.empty() ? "'" : ", '") + name + "'";
  }
  throw NumericalError({"constraint Jacobian", -1, t,
                        "the constraint Jacobian is singular during " + during +
                            (names.empty() ? std::string() : " (dependent: " + names + ")") +
                            "; the mechanism is at a toggle / locked position or a massless part is free",
                        "change the geometry or the driver so the mechanism avoids this position"});
}

void Dynamics::impose_prescribed(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const {
  for (const auto& p : model_.prescribed) {
    q[p.coordinate] = p.reference + p.displacement(t);
    qd[p.coordinate] = p.displacement.d1(t);
  }
}

void Dynamics::derivative(double t, const Eigen::VectorXd& q_in, const Eigen::VectorXd& qd_in, Eigen::VectorXd& qdd,
                          Eigen::Vector3d& power) {
  // imposed motions replace whatever the integrator carried for those coordinates
  const Eigen::VectorXd* qp = &q_in;
  const Eigen::VectorXd* qdp = &qd_in;
  if (!model_.prescribed.empty()) {
    q_work_ = q_in;
    qd_work_ = qd_in;
    impose_prescribed(t, q_work_, qd_work_);
    qp = &q_work_;
    qdp = &qd_work_;
  }
  const Eigen::VectorXd& q = *qp;
  const Eigen::VectorXd& qd = *qdp;
  const int n = model_.coordinate_count;

  // the parts' times come from one evaluation in kTimedEvery, counted that many times: reading
  // the clock four times would cost as much as the rest of a small system's evaluation
  const bool timed = evaluations_++ % kTimedEvery == 0;
  const auto now = [timed] { return timed ? Clock::now() : Clock::time_point{}; };

  // generalised forces: gravity, force elements, peridynamic bodies, the mouse
  auto start = now();
  // gravity, or zeros without it (a write, not a copy, of the whole vector)
  if (has_gravity_)
    g_ = model_.gravity_force;
  else
    g_.setZero(n);
  double dissipated = 0.0, external = 0.0, driver = 0.0;
  for (auto& f : model_.forces) {
    f->add_forces(q, qd, t, g_);
    dissipated += f->dissipation_power(q, qd);
    external += f->external_power(q, qd, t);
  }
  for (auto& flex : model_.flex_bodies) {
    flex->add_forces(q, qd, t, g_);
    if (flex->bond_damping() != 0.0 || flex->global_damping() != 0.0) dissipated += flex->dissipation_power(q, qd);
    external += flex->external_power(q, qd, t);
  }
  // contacts of [[contact]] (an empty list without them)
  for (auto& contact : model_.contacts) dissipated += contact->add_forces_dissipating(q, qd, t, g_);
  if (!held_.empty()) check_held_rotations(model_, held_, g_, t);
  if (mouse_) {
    const Vec2 target = mouse_->target_at(t);
    if (mouse_->point.body >= 0) {
      const Vec2 p = mouse_->point.position(q);
      const Vec2 v = mouse_->point.velocity(q, qd);
      const Vec2 force = mouse_->stiffness * (target - p) - mouse_->damping * v;
      mouse_->point.add_force(g_, force, 1.0, q);
      external += force.dot(v);
    }
    // a held patch of particles: each towards the target plus its offset
    for (size_t k = 0; k < mouse_->particle_coordinates.size(); ++k) {
      const int c = mouse_->particle_coordinates[k];
      const Vec2 p(q[c], q[c + 1]), v(qd[c], qd[c + 1]);
      const Vec2 force = mouse_->particle_stiffness[k] * (target + mouse_->offsets[k] - p) -
                         mouse_->particle_damping[k] * v;
      g_[c] += force.x();
      g_[c + 1] += force.y();
      external += force.dot(v);
    }
  }
  if (timed) force_seconds_ += kTimedEvery * since(start);

  // unconstrained coordinates: qdd = g / m (over every coordinate with mass, one vectorised pass;
  // the others are overwritten below); imposed ones: f''
  qdd.resize(n);
  qdd = g_.cwiseProduct(inverse_mass_);
  for (const auto& p : model_.prescribed) qdd[p.coordinate] = p.displacement.d2(t);

  // constrained coordinates: the augmented system, eliminated attachments condensed
  if (!constrained_.empty()) {
    start = now();
    const int m = active_rows();
    assemble_reduced(t, q);
    gamma_all_.resize(model_.constraint_rows);
    for (const auto& block : model_.constraints) {
      block.constraint->gamma(q, qd, t, gamma_all_.data() + block.first_row);
    }
    time_derivative_all(t, q);
    velocity_residual_all(qd);  // Phi_q qd + Phi_t
    e_all_ = gamma_all_;
    // imposed accelerations move to the right-hand side
    for (const auto& e : prescribed_j_) e_all_[active_[reduced_rows_[e.row()]]] -= e.value() * qdd[e.col()];
    // Baumgarte stabilisation: gamma - 2 alpha Phi_dot - beta^2 Phi
    if (correction_.method == CorrectionDef::Method::kBaumgarte && m > 0) {
      residual_all(t, q);
      const double a2 = 2.0 * correction_.alpha, b2 = correction_.beta * correction_.beta;
      for (int row : active_) e_all_[row] -= a2 * nu_all_[row] + b2 * phi_all_[row];
    }
    if (!solve_constrained(model_.mass, g_.data(), e_all_.data(), kkt_, qdd))
      throw_singular(t, q, "the acceleration solve");
    const int nr = reduced_coordinates();
    for (int r = 0; r < reduced_rows(); ++r) lambda_[reduced_rows_[r]] = x_[nr + r];
    // the rank as the run goes: count each change of the rows left out
    if (dense_ && dense_acceleration_.dependent() != last_dependent_) {
      last_dependent_ = dense_acceleration_.dependent();
      ++rank_changes_;
    }
    condensed_.multipliers(model_.mass, qdd, g_.data(), active_index_, lambda_);

    // drivers do work -lambda (Phi_q qd) on the system (power of the reaction -Phi_q^T lambda)
    for (int a = 0; a < m; ++a) {
      if (active_is_driver_[a]) driver -= lambda_[a] * (nu_all_[active_[a]] - phi_t_all_[active_[a]]);
    }
    // constraint forces on imposed coordinates are part of their reaction
    for (const auto& e : prescribed_j_) g_[e.col()] -= e.value() * lambda_[reduced_rows_[e.row()]];
    if (timed) constraint_seconds_ += kTimedEvery * since(start);
  }
  // imposed motions do the work of their reactions m qdd - g
  for (const auto& p : model_.prescribed) {
    const int c = p.coordinate;
    driver += (model_.mass[c] * qdd[c] - g_[c]) * qd[c];
  }
  power = Eigen::Vector3d(dissipated, external, driver);
}

}  // namespace periflex
