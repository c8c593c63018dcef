// The augmented-system solver against a dense LU of the same matrix, with and without hub
// coordinates (a massless body in more equations than KktSolver::kHubDegree), and the reuse of
// its pattern analysis while the structure of the Jacobian stays.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "solve/kkt_solver.h"

namespace periflex {
namespace {

// n particles of mass 1e-6 attached to a massless body (coordinates 0..2), plus one equation
// on the body alone (a driver), and a second body of mass 2 tied to particle 0.
void check(int n, bool expect_hubs) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nc = 3 + 2 * n + 3;
  Eigen::VectorXd w = Eigen::VectorXd::Constant(nc, 1e-6);
  w.head(3).setZero();
  w.tail(3) << 2.0, 2.0, 0.1;
  Triplets j;
  int row = 0;
  for (int p = 0; p < n; ++p) {
    for (int k = 0; k < 2; ++k, ++row) {
      j.emplace_back(row, k, 1.0);
      j.emplace_back(row, 2, u(rng));
      j.emplace_back(row, 3 + 2 * p + k, -1.0);
    }
  }
  j.emplace_back(row++, 2, 1.0);  // driver on the body's angle
  for (int k = 0; k < 2; ++k, ++row) {  // pin between the heavy body and particle 0
    j.emplace_back(row, 3 + 2 * n + k, 1.0);
    j.emplace_back(row, 3 + 2 * n + 2, u(rng));
    j.emplace_back(row, 3 + k, -1.0);
  }
  const int m = row;
  KktSolver solver;
  ASSERT_TRUE(solver.factorize(w, j, m));
  EXPECT_EQ(solver.hub_unknowns() > 0, expect_hubs);

  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(nc + m, nc + m);
  for (int i = 0; i < nc; ++i) k(i, i) = w[i];
  for (const auto& e : j) {
    k(nc + e.row(), e.col()) += e.value();
    k(e.col(), nc + e.row()) += e.value();
  }
  Eigen::VectorXd rhs(nc + m);
  for (int i = 0; i < nc + m; ++i) rhs[i] = u(rng);
  const Eigen::VectorXd x = solver.solve(rhs);
  const Eigen::VectorXd reference = k.fullPivLu().solve(rhs);
  // both are backward stable; the matrix spans masses 1e-6..2, so compare relative to |x|
  EXPECT_LT((x - reference).norm(), 1e-8 * reference.norm());
  EXPECT_LT((k * x - rhs).norm(), 1e-9 * (k.norm() * x.norm() + rhs.norm()));
}

// A chain of n coordinates, each tied to the one before by x_{r+1} - slope x_r (slope below 1:
// well conditioned); `extra` adds an equation on the first coordinate alone.
Triplets chain(int n, double slope, bool extra, int& m) {
  Triplets j;
  m = 0;
  for (int r = 0; r + 1 < n; ++r, ++m) {
    j.emplace_back(m, r, -slope);
    j.emplace_back(m, r + 1, 1.0);
  }
  if (extra) j.emplace_back(m++, 0, 1.0);
  return j;
}

// Solves with `solver` and with a dense LU of the same matrix; the largest difference relative
// to the largest entry of the solution.
double against_dense(KktSolver& solver, const Eigen::VectorXd& w, const Triplets& j, int m) {
  const int n = static_cast<int>(w.size());
  EXPECT_TRUE(solver.factorize(w, j, m));
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + m, n + m);
  for (int i = 0; i < n; ++i) k(i, i) = w[i];
  for (const auto& e : j) {
    k(n + e.row(), e.col()) += e.value();
    k(e.col(), n + e.row()) += e.value();
  }
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n + m, -1.0, 2.0);
  const Eigen::VectorXd reference = k.fullPivLu().solve(rhs);
  return (solver.solve(rhs) - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

TEST(KktSolver, PatternIsAnalysedOnceWhileTheStructureStaysAndAgainWhenItChanges) {
  // the values change at every factorisation (as the Jacobian does along a run), the structure
  // does not: one analysis, and every solve still matches a dense LU of its own matrix
  KktSolver solver;
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(40, 1.0, 3.0);
  int m = 0;
  for (int k = 0; k < 6; ++k) {
    const Triplets j = chain(40, 0.5 + 0.1 * k, false, m);
    EXPECT_LT(against_dense(solver, w, j, m), 1e-12) << "factorisation " << k;
  }
  EXPECT_EQ(solver.analyses(), 1);
  // an equation more: a new structure, analysed once more; then the first structure again
  const Triplets more = chain(40, 0.7, true, m);
  EXPECT_LT(against_dense(solver, w, more, m), 1e-12);
  EXPECT_EQ(solver.analyses(), 2);
  const Triplets back = chain(40, 0.9, false, m);
  EXPECT_LT(against_dense(solver, w, back, m), 1e-12);
  EXPECT_EQ(solver.analyses(), 3);
}

TEST(KktSolver, MatchesDenseSolveWithoutHubs) { check(10, false); }
TEST(KktSolver, MatchesDenseSolveWithHubs) { check(100, true); }

}  // namespace
}  // namespace periflex
