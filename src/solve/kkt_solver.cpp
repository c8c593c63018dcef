#include "solve/kkt_solver.h"

#include <algorithm>
#include <cmath>

namespace periflex {

bool KktSolver::factorize(const Eigen::VectorXd& w, const Triplets& jacobian, int m, const Triplets* coupling) {
  const int n = static_cast<int>(w.size());
  // scaling: 1/sqrt(w) for coordinates with mass, then each equation to a unit largest entry
  scale_.resize(n + m);
  for (int i = 0; i < n; ++i) scale_[i] = w[i] > 0.0 ? 1.0 / std::sqrt(w[i]) : 1.0;
  scale_.tail(m).setZero();
  for (const auto& e : jacobian) {
    scale_[n + e.row()] = std::max(scale_[n + e.row()], std::abs(e.value()) * scale_[e.col()]);
  }
  for (int r = 0; r < m; ++r) scale_[n + r] = scale_[n + r] > 0.0 ? 1.0 / scale_[n + r] : 1.0;

  // hubs: coordinates in many equations
  if (!split_failed_) {
    std::vector<int> degree(n, 0);
    for (const auto& e : jacobian) ++degree[e.col()];
    if (std::any_of(degree.begin(), degree.end(), [](int d) { return d > kHubDegree; })) {
      if (factorize_split(w, jacobian, m, coupling)) return true;
      split_failed_ = true;  // singular split: factorise the whole matrix from now on
    }
  }
  hub_.clear();

  // the whole scaled matrix; diagonal entries always stored so the pattern never changes
  triplets_.clear();
  triplets_.reserve(n + 2 * jacobian.size());
  for (int i = 0; i < n; ++i) triplets_.emplace_back(i, i, w[i] * scale_[i] * scale_[i]);
  if (coupling)
    for (const auto& e : *coupling) triplets_.emplace_back(e.row(), e.col(), e.value() * scale_[e.row()] * scale_[e.col()]);
  for (const auto& e : jacobian) {
    const double v = e.value() * scale_[e.col()] * scale_[n + e.row()];
    triplets_.emplace_back(n + e.row(), e.col(), v);
    triplets_.emplace_back(e.col(), n + e.row(), v);
  }
  return factorize_sparse(triplets_, n + m);
}

bool KktSolver::factorize_sparse(const Triplets& triplets, int size) {
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  // re-analyse only when the pattern differs from the analysed one
  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  const int nnz = static_cast<int>(matrix_.nonZeros());
  const bool same = outer_.size() == static_cast<size_t>(size + 1) && inner_.size() == static_cast<size_t>(nnz) &&
                    std::equal(outer_.begin(), outer_.end(), outer) && std::equal(inner_.begin(), inner_.end(), inner);
  if (!same) {
    outer_.assign(outer, outer + size + 1);
    inner_.assign(inner, inner + nnz);
    lu_.setPivotThreshold(0.01);
    lu_.analyzePattern(matrix_);
    ++analyses_;
  }
  lu_.factorize(matrix_);
  return lu_.info() == Eigen::Success;
}

bool KktSolver::factorize_split(const Eigen::VectorXd& w, const Triplets& jacobian, int m,
                                const Triplets* coupling) {
  const int n = static_cast<int>(w.size());
  std::vector<int> degree(n, 0);
  for (const auto& e : jacobian) ++degree[e.col()];
  // hub unknowns: hub coordinates, and equations that involve hub coordinates only
  std::vector<char> is_hub(n + m, 0), row_has_other(m, 0);
  for (int i = 0; i < n; ++i) is_hub[i] = degree[i] > kHubDegree;
  for (const auto& e : jacobian) {
    if (!is_hub[e.col()]) row_has_other[e.row()] = 1;
  }
  for (int r = 0; r < m; ++r) is_hub[n + r] = !row_has_other[r];
  sparse_.clear();
  hub_.clear();
  position_.assign(n + m, -1);
  for (int u = 0; u < n + m; ++u) {
    auto& part = is_hub[u] ? hub_ : sparse_;
    position_[u] = static_cast<int>(part.size());
    part.push_back(u);
  }
  const int ns = static_cast<int>(sparse_.size()), nh = static_cast<int>(hub_.size());

  // blocks of the scaled matrix: A (sparse part), B (sparse x hub), C (hub x hub)
  triplets_.clear();
  coupling_ = Eigen::MatrixXd::Zero(ns, nh);
  Eigen::MatrixXd corner = Eigen::MatrixXd::Zero(nh, nh);
  auto put = [&](int a, int b, double v) {
    if (!is_hub[a] && !is_hub[b]) {
      triplets_.emplace_back(position_[a], position_[b], v);
    } else if (!is_hub[a]) {
      coupling_(position_[a], position_[b]) += v;
    } else if (is_hub[a] && is_hub[b]) {
      corner(position_[a], position_[b]) += v;
    }
  };
  for (int i = 0; i < n; ++i) put(i, i, w[i] * scale_[i] * scale_[i]);
  if (coupling)
    for (const auto& e : *coupling) put(e.row(), e.col(), e.value() * scale_[e.row()] * scale_[e.col()]);
  for (const auto& e : jacobian) {
    const double v = e.value() * scale_[e.col()] * scale_[n + e.row()];
    put(n + e.row(), e.col(), v);
    put(e.col(), n + e.row(), v);
  }
  if (!factorize_sparse(triplets_, ns)) return false;

  // Schur complement of the hubs: S = C - B^T A^-1 B (dense, a few unknowns per hub)
  solved_coupling_ = lu_.solve(coupling_);
  const Eigen::MatrixXd schur = corner - coupling_.transpose() * solved_coupling_;
  if (!solved_coupling_.allFinite() || !schur.allFinite()) return false;
  // equilibrate S (hub coordinates and equations on them differ by many orders of magnitude:
  // S is itself a small saddle-point matrix), then check its pivots against unit scale
  schur_scale_ = Eigen::VectorXd::Ones(nh);
  for (int pass = 0; pass < 8; ++pass) {
    for (int r = 0; r < nh; ++r) {
      double largest = 0.0;
      for (int c = 0; c < nh; ++c) largest = std::max(largest, std::abs(schur(r, c)) * schur_scale_[r] * schur_scale_[c]);
      if (largest > 0.0) schur_scale_[r] /= std::sqrt(largest);
    }
  }
  schur_.compute(schur_scale_.asDiagonal() * schur * schur_scale_.asDiagonal());
  const Eigen::MatrixXd u = schur_.matrixLU().triangularView<Eigen::Upper>();
  for (int k = 0; k < nh; ++k) {
    if (!(std::abs(u(k, k)) > 1e-12)) return false;
  }
  return true;
}

// K x = b  <=>  (D K D) (D^-1 x) = D b.
Eigen::VectorXd KktSolver::solve(const Eigen::VectorXd& rhs) const {
  const Eigen::VectorXd scaled = scale_.cwiseProduct(rhs);
  Eigen::VectorXd y(scaled.size());
  if (hub_.empty()) {
    y = lu_.solve(scaled);
  } else {
    // block elimination: A z = b_s; S x_h = b_h - B^T z; x_s = z - A^-1 B x_h
    Eigen::VectorXd bs(sparse_.size()), bh(hub_.size());
    for (size_t k = 0; k < sparse_.size(); ++k) bs[k] = scaled[sparse_[k]];
    for (size_t k = 0; k < hub_.size(); ++k) bh[k] = scaled[hub_[k]];
    const Eigen::VectorXd z = lu_.solve(bs);
    const Eigen::VectorXd rh = schur_scale_.cwiseProduct(bh - coupling_.transpose() * z);
    const Eigen::VectorXd xh = schur_scale_.cwiseProduct(schur_.solve(rh));
    const Eigen::VectorXd xs = z - solved_coupling_ * xh;
    for (size_t k = 0; k < sparse_.size(); ++k) y[sparse_[k]] = xs[k];
    for (size_t k = 0; k < hub_.size(); ++k) y[hub_[k]] = xh[k];
  }
  return scale_.cwiseProduct(y);
}

}  // namespace periflex
