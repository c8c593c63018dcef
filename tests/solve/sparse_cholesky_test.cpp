// The supernodal Cholesky on a grid's stiffness-plus-mass matrix: solutions against a dense
// factorisation, a refactorisation with new values, and an indefinite matrix refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "solve/sparse_cholesky.h"

namespace periflex {
namespace {

// M + K on an nx x ny grid (one unknown per node, neighbours within two spacings), as a dense
// matrix; `shift` is added to the diagonal.
Eigen::MatrixXd grid_matrix(int nx, int ny, unsigned seed, double shift) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  const int n = nx * ny;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) += u(rng) + shift;
    for (int j = i + 1; j < n; ++j) {
      const int dx = j % nx - i % nx, dy = j / nx - i / nx;
      if (dx * dx + dy * dy > 4) continue;
      const double k = u(rng);
      a(i, i) += k;
      a(j, j) += k;
      a(i, j) -= k;
      a(j, i) -= k;
    }
  }
  return a;
}

// The lower triangle of a in compressed columns.
void lower_triangle(const Eigen::MatrixXd& a, std::vector<int>& start, std::vector<int>& rows,
                    std::vector<double>& values) {
  start.assign(1, 0);
  rows.clear();
  values.clear();
  for (int j = 0; j < a.cols(); ++j) {
    for (int i = j; i < a.rows(); ++i)
      if (i == j || a(i, j) != 0.0) {
        rows.push_back(i);
        values.push_back(a(i, j));
      }
    start.push_back(static_cast<int>(rows.size()));
  }
}

TEST(SparseCholesky, SolvesAsADenseFactorisationDoes) {
  const Eigen::MatrixXd a = grid_matrix(30, 20, 1, 0.0);
  std::vector<int> start, rows;
  std::vector<double> values;
  lower_triangle(a, start, rows, values);
  SparseCholesky chol;
  chol.analyse(static_cast<int>(a.rows()), start, rows);
  ASSERT_TRUE(chol.factorize(values.data()));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 3.0);
  Eigen::VectorXd x;
  chol.solve(b, x);
  const Eigen::VectorXd expected = a.llt().solve(b);
  EXPECT_LT((x - expected).norm() / expected.norm(), 1e-12);
  EXPECT_GT(chol.factor_entries(), static_cast<long>(rows.size()));  // fill
}

TEST(SparseCholesky, RefactorisesNewValuesOnThePattern) {
  const Eigen::MatrixXd a = grid_matrix(20, 20, 2, 0.0), a2 = grid_matrix(20, 20, 3, 0.0);
  std::vector<int> start, rows, start2, rows2;
  std::vector<double> values, values2;
  lower_triangle(a, start, rows, values);
  lower_triangle(a2, start2, rows2, values2);
  ASSERT_EQ(rows, rows2);
  SparseCholesky chol;
  chol.analyse(static_cast<int>(a.rows()), start, rows);
  ASSERT_TRUE(chol.factorize(values.data()));
  ASSERT_TRUE(chol.factorize(values2.data()));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(a.rows());
  Eigen::VectorXd x;
  chol.solve(b, x);
  const Eigen::VectorXd expected = a2.llt().solve(b);
  EXPECT_LT((x - expected).norm() / expected.norm(), 1e-12);
}

TEST(SparseCholesky, IndefiniteOrNonFiniteIsRefused) {
  const Eigen::MatrixXd a = grid_matrix(15, 10, 4, -6.0);  // shifted below its smallest eigenvalue
  ASSERT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues()[0], 0.0);
  std::vector<int> start, rows;
  std::vector<double> values;
  lower_triangle(a, start, rows, values);
  SparseCholesky chol;
  chol.analyse(static_cast<int>(a.rows()), start, rows);
  EXPECT_FALSE(chol.factorize(values.data()));
  Eigen::VectorXd x;
  chol.solve(Eigen::VectorXd::Ones(a.rows()), x);
  EXPECT_FALSE(x.allFinite());
  // positive definite again, then a NaN among the values
  const Eigen::MatrixXd good = grid_matrix(15, 10, 4, 0.0);
  lower_triangle(good, start, rows, values);
  EXPECT_TRUE(chol.factorize(values.data()));
  values[3] = std::nan("");
  EXPECT_FALSE(chol.factorize(values.data()));
}

}  // namespace
}  // namespace periflex
