// Projections of Dynamics onto the constraints: positions (Newton iterations on the rows that
// stay) and velocities after a step, and the violations they are judged by.
#include "solve/dynamics.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace periflex {

double Dynamics::project_positions(double t, Eigen::VectorXd& q, double tolerance, int max_iterations) {
  if (active_.empty()) return 0.0;
  double error = position_violation(t, q);
  // Newton on min (dq^T W dq) subject to Phi(q + dq) = 0
  for (int it = 0; it < max_iterations && error > tolerance; ++it) {
    assemble_reduced(t, q);
    e_all_ = -phi_all_;
    dz_.setZero(model_.coordinate_count);
    if (!solve_constrained(weight_, nullptr, e_all_.data(), projection_kkt_, dz_))
      throw_singular(t, q, "the position projection");
    for (int c : constrained_) q[c] += dz_[c];
    error = position_violation(t, q);
    // with rank monitoring, converged once the rows this solve kept are satisfied (a row left
    // out depends on them to first order; its residual still shows in position_violation)
    if (dense_) error = selected_violation();
    if (!dense_ && !dropped_.empty()) {
      error = 0.0;
      for (int row : active_) error = std::max(error, std::abs(phi_all_[row]));
      if (!std::isfinite(error)) error = std::numeric_limits<double>::infinity();
    }
  }
  return error;
}

double Dynamics::project_positions_from(double t, const Eigen::VectorXd& q_start, Eigen::VectorXd& q,
                                        double tolerance, int max_iterations) {
  if (!dense_) return project_positions(t, q, tolerance, max_iterations);
  // the normals at the start, and the rows independent there (rank-revealing QR in the weights)
  const int nr = static_cast<int>(reduced_cols_.size());
  assemble_reduced(t, q_start);
  Eigen::MatrixXd& j = dense_projection_.jacobian();
  j.setZero();
  for (const auto& e : reduced_j_) j(e.row(), e.col()) += e.value();
  start_j_ = j;
  select_.resize(nr);
  diag_.resize(nr);
  for (int k = 0; k < nr; ++k) {
    select_[k] = selection_[reduced_cols_[k]];
    diag_[k] = weight_[reduced_cols_[k]];
  }
  if (!dense_projection_.factorize(diag_.data(), select_.data(), kRankThreshold))
    throw_singular(t, q_start, "the position projection");
  std::vector<int> rows;
  for (int r = 0; r < static_cast<int>(active_.size()); ++r) {
    if (!std::binary_search(dense_projection_.dependent().begin(), dense_projection_.dependent().end(), r))
      rows.push_back(r);
  }
  const int m = static_cast<int>(rows.size());
  residual_all(t, q);
  double error = selected_violation();
  for (int it = 0; it < max_iterations && error > tolerance; ++it) {
    // (J_k W^-1 J_0^T) dmu = -Phi, dq = W^-1 J_0^T dmu
    assemble_reduced(t, q);
    j.setZero();
    for (const auto& e : reduced_j_) j(e.row(), e.col()) += e.value();
    shake_matrix_.resize(m, m);
    shake_rhs_.resize(m);
    for (int a = 0; a < m; ++a) {
      shake_rhs_[a] = -phi_all_[rows[a]];
      for (int b = 0; b < m; ++b) {
        double v = 0.0;
        for (int k = 0; k < nr; ++k) v += j(rows[a], k) * start_j_(rows[b], k) / diag_[k];
        shake_matrix_(a, b) = v;
      }
    }
    shake_lu_.compute(shake_matrix_);
    const Eigen::VectorXd mu = shake_lu_.solve(shake_rhs_);
    if (!mu.allFinite()) throw_singular(t, q, "the position projection");
    for (int k = 0; k < nr; ++k) {
      double v = 0.0;
      for (int b = 0; b < m; ++b) v += start_j_(rows[b], k) * mu[b];
      q[reduced_cols_[k]] += v / diag_[k];
    }
    residual_all(t, q);
    error = selected_violation();
  }
  return error;
}

double Dynamics::selected_violation() const {
  const auto& left_out = dense_projection_.dependent();
  double worst = 0.0;
  for (int row = 0; row < model_.constraint_rows; ++row) {
    if (std::binary_search(left_out.begin(), left_out.end(), row)) continue;
    worst = std::max(worst, std::abs(phi_all_[row]));
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

double Dynamics::project_velocities(double t, const Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  if (active_.empty()) return 0.0;
  assemble_reduced(t, q);
  time_derivative_all(t, q);
  velocity_residual_all(qd);
  // the correction dqd solves [W J^T; J 0][dqd; mu] = [0; -(Phi_q qd + Phi_t)]
  e_all_ = -nu_all_;
  dz_.setZero(model_.coordinate_count);
  if (!solve_constrained(weight_, nullptr, e_all_.data(), projection_kkt_, dz_))
    throw_singular(t, q, "the velocity projection");
  double change = 0.0;
  for (int c : constrained_) {
    qd[c] += dz_[c];
    change = std::max(change, std::abs(dz_[c]));
  }
  return change;
}

double Dynamics::position_violation(double t, const Eigen::VectorXd& q) {
  if (active_.empty()) return 0.0;
  // every row, the ones dropped as dependent included: their violation is part of the figure
  residual_all(t, q);
  double worst = 0.0;
  for (int row = 0; row < model_.constraint_rows; ++row) worst = std::max(worst, std::abs(phi_all_[row]));
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

double Dynamics::velocity_violation(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (active_.empty()) return 0.0;
  assemble_reduced(t, q);
  time_derivative_all(t, q);
  velocity_residual_all(qd);
  double worst = 0.0;
  for (int row : active_) worst = std::max(worst, std::abs(nu_all_[row]));
  // the rows left out as dependent: Phi_q qd + Phi_t from their blocks' Jacobians
  if (!dense_ && !dropped_.empty()) {
    all_.clear();
    for (const auto& block : model_.constraints) {
      const int first = block.first_row, count = block.constraint->rows();
      const auto it = std::lower_bound(dropped_.begin(), dropped_.end(), first);
      if (it == dropped_.end() || *it >= first + count) continue;
      block.constraint->jacobian(q, t, first, all_);
    }
    Eigen::VectorXd& left_out = dz_;
    left_out = phi_t_all_;
    for (const auto& e : all_) left_out[e.row()] += e.value() * qd[e.col()];
    for (int row : dropped_) worst = std::max(worst, std::abs(left_out[row]));
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

}  // namespace periflex
