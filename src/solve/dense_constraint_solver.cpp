#include "solve/dense_constraint_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace periflex {

void DenseConstraintSolver::resize(int n, int m) {
  n_ = n;
  m_ = m;
  j_.setZero(m, n);
  v_.resize(n);
  null_.resize(n, n);
  reduced_.resize(n, n);
  qr_.resize(n, m);
  tau_.resize(std::min(n, m));
  norm2_.resize(m);
  perm_.resize(m);
  late_.assign(m, 0);
  s_.resize(n);
  rho_.resize(m);
  b_.resize(n);
  c_.resize(n);
  x_.resize(n);
  d_.resize(n);
  e_.resize(n);
  selected_.reserve(m);
  dependent_.reserve(m);
}

void DenseConstraintSolver::set_late_rows(const std::vector<int>& rows) {
  late_.assign(m_, 0);
  for (int r : rows) late_[r] = 1;
}

void DenseConstraintSolver::apply_q_transpose(Eigen::VectorXd& v, int count) const {
  for (int k = 0; k < count; ++k) {
    // H_k = I - tau_k u u^T with u = [1; qr_(k+1:n, k)]
    double dot = v[k];
    for (int i = k + 1; i < n_; ++i) dot += qr_(i, k) * v[i];
    dot *= tau_[k];
    v[k] -= dot;
    for (int i = k + 1; i < n_; ++i) v[i] -= dot * qr_(i, k);
  }
}

void DenseConstraintSolver::apply_q(Eigen::VectorXd& v, int count) const {
  for (int k = count - 1; k >= 0; --k) {
    double dot = v[k];
    for (int i = k + 1; i < n_; ++i) dot += qr_(i, k) * v[i];
    dot *= tau_[k];
    v[k] -= dot;
    for (int i = k + 1; i < n_; ++i) v[i] -= dot * qr_(i, k);
  }
}

bool DenseConstraintSolver::factorize(const double* w, const double* select, double threshold) {
  // columns of A: the rows of J in the selection metric S = W_select^-1/2, each of unit length
  positive_ = true;
  for (int c = 0; c < n_; ++c) {
    s_[c] = 1.0 / std::sqrt(select[c]);
    positive_ = positive_ && w[c] == select[c];
  }
  for (int r = 0; r < m_; ++r) {
    double norm2 = 0.0;
    for (int c = 0; c < n_; ++c) {
      qr_(c, r) = j_(r, c) * s_[c];
      norm2 += qr_(c, r) * qr_(c, r);
    }
    rho_[r] = std::sqrt(norm2);
    if (rho_[r] > 0.0) {
      const double inverse = 1.0 / rho_[r];
      for (int c = 0; c < n_; ++c) qr_(c, r) *= inverse;
    }
  }
  // Householder QR with column pivoting: at each step the column with the largest remaining
  // norm among the rows not marked late, then among the late ones; stop when none is above
  // the threshold (the rest depend on the columns taken)
  for (int r = 0; r < m_; ++r) {
    perm_[r] = r;
    norm2_[r] = rho_[r] > 0.0 ? 1.0 : 0.0;
  }
  const int steps = std::min(n_, m_);
  const double floor2 = threshold * threshold;
  rank_ = 0;
  smallest_pivot_ = 1.0;
  for (int k = 0; k < steps; ++k) {
    int pick = -1;
    for (int pass = 0; pass < 2 && pick < 0; ++pass) {
      double best = floor2;
      for (int c = k; c < m_; ++c) {
        if (late_[perm_[c]] != pass) continue;
        if (norm2_[c] > best) {
          best = norm2_[c];
          pick = c;
        }
      }
    }
    if (pick < 0) break;
    if (pick != k) {
      qr_.col(k).swap(qr_.col(pick));
      std::swap(perm_[k], perm_[pick]);
      std::swap(norm2_[k], norm2_[pick]);
    }
    // reflector zeroing qr_(k+1:n, k)
    double tail = 0.0;
    for (int i = k + 1; i < n_; ++i) tail += qr_(i, k) * qr_(i, k);
    const double head = qr_(k, k);
    const double alpha = -std::copysign(std::sqrt(head * head + tail), head);
    const double u0 = head - alpha;
    tau_[k] = -u0 / alpha;
    for (int i = k + 1; i < n_; ++i) qr_(i, k) /= u0;
    qr_(k, k) = alpha;
    for (int c = k + 1; c < m_; ++c) {
      double dot = qr_(k, c);
      for (int i = k + 1; i < n_; ++i) dot += qr_(i, k) * qr_(i, c);
      dot *= tau_[k];
      qr_(k, c) -= dot;
      for (int i = k + 1; i < n_; ++i) qr_(i, c) -= dot * qr_(i, k);
      // remaining norm below row k, recomputed (small matrices: exact and cheap)
      double rest = 0.0;
      for (int i = k + 1; i < n_; ++i) rest += qr_(i, c) * qr_(i, c);
      norm2_[c] = rest;
    }
    smallest_pivot_ = std::min(smallest_pivot_, std::abs(alpha));
    ++rank_;
  }
  selected_.assign(perm_.begin(), perm_.begin() + rank_);
  dependent_.assign(perm_.begin() + rank_, perm_.end());
  std::sort(dependent_.begin(), dependent_.end());
  if (positive_) return true;

  // massless coordinates: the part of x the selected rows leave free is x = N v, with N = Q2 the
  // columns of Q past the rank (an orthonormal basis of what the selected rows do not see), and
  // N^T D N v = N^T (b - D x1) fixes it, D = W S^2 (one where there is mass, zero where there is
  // none). The same QR serves; the reduced matrix is small and positive definite unless a
  // massless direction escapes every selected row (then the solve is refused)
  const int p = n_ - rank_;
  for (int c = 0; c < n_; ++c) d_[c] = w[c] * s_[c] * s_[c];
  for (int j = 0; j < p; ++j) {
    e_.setZero();
    e_[rank_ + j] = 1.0;
    apply_q(e_, rank_);
    null_.col(j) = e_;
  }
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j <= i; ++j) {
      double v = 0.0;
      for (int c = 0; c < n_; ++c) v += null_(c, i) * d_[c] * null_(c, j);
      reduced_(i, j) = reduced_(j, i) = v;
    }
  }
  if (p == 0) return true;
  // Cholesky in place (lower triangle), written out: the matrix has a handful of rows, where a
  // general blocked factorisation costs more in set-up than in arithmetic. A pivot at round-off
  // level of the largest weight: a massless direction no row holds.
  const double floor = 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, d_.maxCoeff()) * n_;
  for (int j = 0; j < p; ++j) {
    double pivot = reduced_(j, j);
    for (int k = 0; k < j; ++k) pivot -= reduced_(j, k) * reduced_(j, k);
    if (!(pivot > floor)) return false;
    const double root = std::sqrt(pivot);
    reduced_(j, j) = root;
    for (int i = j + 1; i < p; ++i) {
      double v = reduced_(i, j);
      for (int k = 0; k < j; ++k) v -= reduced_(i, k) * reduced_(j, k);
      reduced_(i, j) = v / root;
    }
  }
  return true;
}

void DenseConstraintSolver::solve(const double* a, const double* e, double* z, double* mu) {
  // b = S a, e~ = e / rho on the selected rows
  for (int c = 0; c < n_; ++c) b_[c] = a ? s_[c] * a[c] : 0.0;
  for (int r = 0; r < m_; ++r) mu[r] = 0.0;
  const Eigen::MatrixXd& r = qr_;
  if (!positive_) {
    // x1 = Q1 R11^-T e~, then x = x1 + N v with N^T D N v = N^T (b - D x1)
    for (int k = 0; k < rank_; ++k) {
      double y = e[selected_[k]] / rho_[selected_[k]];
      for (int i = 0; i < k; ++i) y -= r(i, k) * x_[i];
      x_[k] = y / r(k, k);
    }
    for (int k = rank_; k < n_; ++k) x_[k] = 0.0;
    apply_q(x_, rank_);
    const int p = n_ - rank_;
    if (p > 0) {
      for (int c = 0; c < n_; ++c) c_[c] = b_[c] - d_[c] * x_[c];
      // v = N^T c, then L L^T v = v (forward and back substitution), then x += N v
      for (int j = 0; j < p; ++j) {
        double v = 0.0;
        for (int c = 0; c < n_; ++c) v += null_(c, j) * c_[c];
        for (int k = 0; k < j; ++k) v -= reduced_(j, k) * v_[k];
        v_[j] = v / reduced_(j, j);
      }
      for (int j = p - 1; j >= 0; --j) {
        double v = v_[j];
        for (int k = j + 1; k < p; ++k) v -= reduced_(k, j) * v_[k];
        v_[j] = v / reduced_(j, j);
      }
      for (int j = 0; j < p; ++j)
        for (int c = 0; c < n_; ++c) x_[c] += null_(c, j) * v_[j];
    }
    // multipliers: R11 mu~ = Q1^T (b - D x)
    for (int c = 0; c < n_; ++c) c_[c] = b_[c] - d_[c] * x_[c];
    apply_q_transpose(c_, rank_);
    for (int k = rank_ - 1; k >= 0; --k) {
      double v = c_[k];
      for (int i = k + 1; i < rank_; ++i) v -= r(k, i) * c_[i];
      c_[k] = v / r(k, k);
    }
    for (int k = 0; k < rank_; ++k) mu[selected_[k]] = c_[k] / rho_[selected_[k]];
    for (int c = 0; c < n_; ++c) z[c] = s_[c] * x_[c];
    return;
  }
  // y = R11^-T e~ (forward substitution), c = Q1^T b
  c_ = b_;
  apply_q_transpose(c_, rank_);
  for (int k = 0; k < rank_; ++k) {
    double y = e[selected_[k]] / rho_[selected_[k]];
    for (int i = 0; i < k; ++i) y -= r(i, k) * x_[i];
    x_[k] = y / r(k, k);  // x_ holds y for now
  }
  // d = c - y over the selected part; multipliers R11 mu~ = d (back substitution)
  for (int k = 0; k < rank_; ++k) x_[k] = c_[k] - x_[k];
  for (int k = rank_ - 1; k >= 0; --k) {
    double v = x_[k];
    for (int i = k + 1; i < rank_; ++i) v -= r(k, i) * c_[i];
    c_[k] = v / r(k, k);  // c_ holds mu~ on the selected part now
  }
  for (int k = 0; k < rank_; ++k) mu[selected_[k]] = c_[k] / rho_[selected_[k]];
  // x = b - Q [d; 0], z = S x
  for (int k = rank_; k < n_; ++k) x_[k] = 0.0;
  apply_q(x_, rank_);
  for (int c = 0; c < n_; ++c) z[c] = s_[c] * (b_[c] - x_[c]);
}

}  // namespace periflex
