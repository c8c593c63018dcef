// The augmented-system solver against a dense LU of the same matrix, with and without hub
// coordinates (a massless body in more equations than KktSolver::kHubDegree).
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

TEST(KktSolver, MatchesDenseSolveWithoutHubs) { check(10, false); }
TEST(KktSolver, MatchesDenseSolveWithHubs) { check(100, true); }

}  // namespace
}  // namespace periflex
