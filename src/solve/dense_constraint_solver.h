// The constrained solve of a small system, dense, with the rank of the constraint Jacobian
// found at every solve:
//   [ W   J^T ] [ z  ]   [ a ]
//   [ J   0   ] [ mu ] = [ e ].
// The rows of J, scaled to unit length in the metric of the selection weights, go through a
// column-pivoted Householder QR; a row whose pivot falls below the threshold depends (to that
// tolerance) on the rows before it and is left out of this solve (its multiplier is zero).
// Rows marked "late" (the ones found dependent at set-up) are pivoted only after every other
// row, so a mechanism with a permanently redundant row leaves out that same row throughout.
// Rows are re-selected at every factorisation, so a mechanism that passes a singular position
// loses the rows only while it is there and gets them back afterwards.
//
// When the weights are the selection weights the QR itself solves the system (z = W^-1/2 x,
// x = b - Q1 (Q1^T b - R11^-T e~)); otherwise (massless or nearly massless bodies, whose
// selection weight is raised) the same QR with the null-space method does: the part the rows fix
// from R11, the rest from a small positive definite system over Q2 (refused when singular: a
// massless direction that no selected row holds). Buffers are kept between solves: no
// allocation in a solve, nor in a factorisation while the rank stays.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace periflex {

class DenseConstraintSolver {
 public:
  // n coordinates, m equations; keeps the buffers for these sizes.
  void resize(int n, int m);
  // Rows to pivot last (size m, nonzero: late); all rows equal when never called.
  void set_late_rows(const std::vector<int>& rows);
  // The Jacobian (m x n) to fill before factorize().
  Eigen::MatrixXd& jacobian() { return j_; }
  // Factorises for the diagonal w (zeros allowed) with rows selected in the metric of
  // `select` (all positive). Rows with a scaled pivot below
  // `threshold` are dependent. False when the selected system is singular (a massless
  // coordinate the selected rows do not fix).
  bool factorize(const double* w, const double* select, double threshold);
  // z (size n) and mu (size m; zero on dependent rows) for the right-hand side a (n, may be
  // null: zero) and e (m).
  void solve(const double* a, const double* e, double* z, double* mu);
  // Independent rows in the last factorisation, and the dependent ones (increasing).
  int rank() const { return rank_; }
  const std::vector<int>& dependent() const { return dependent_; }
  // Smallest scaled pivot among the selected rows (1: orthogonal rows; near the threshold: a
  // singular position is near).
  double smallest_pivot() const { return smallest_pivot_; }

 private:
  int n_ = 0, m_ = 0, rank_ = 0;
  bool positive_ = true;
  double smallest_pivot_ = 1.0;
  Eigen::MatrixXd j_;
  Eigen::VectorXd s_, rho_, b_, c_, x_;
  Eigen::MatrixXd qr_;               // Householder vectors below the diagonal, R above
  Eigen::VectorXd tau_, norm2_;      // reflector factors; remaining squared column norms
  std::vector<int> perm_;            // column k of qr_ is row perm_[k] of J
  std::vector<char> late_;
  // Applies H_{count-1} ... H_0 (transpose) or H_0 ... H_{count-1} to v.
  void apply_q_transpose(Eigen::VectorXd& v, int count) const;
  void apply_q(Eigen::VectorXd& v, int count) const;
  // massless coordinates: D = W S^2, the null-space basis N = Q2 (its first n - rank columns)
  // and N^T D N, factorised in place (its lower triangle holds L of L L^T); kept n x n
  Eigen::VectorXd d_, e_, v_;
  Eigen::MatrixXd null_, reduced_;
  std::vector<int> selected_, dependent_;
};

}  // namespace periflex
