// The symmetric-order sparse LU on matrices shaped like an implicit integrator's iteration
// matrix on a particle grid (two unknowns per particle, coupled within a horizon of three
// spacings, unsymmetric values): solutions against Eigen's SparseLU with its own column order,
// refactorisation on the same pattern, pivoting away from a zero diagonal, and the fill it
// keeps against the fill of a symmetric factorisation in the same order and, where regions are
// coupled whole, against COLAMD's column order.
#include <gtest/gtest.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <random>
#include <vector>

#include "solve/sparse_lu.h"

namespace periflex {
namespace {

// I + c K on an nx x ny grid: every pair of particles within three spacings coupled by a 2x2
// block of random values (unsymmetric), the diagonal made dominant unless `zero_diagonal`
// names an unknown whose diagonal is left at zero.
Eigen::SparseMatrix<double> grid_matrix(int nx, int ny, unsigned seed, int zero_diagonal = -1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 2 * nx * ny;
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> row_sum(n, 0.0);
  for (int i = 0; i < nx * ny; ++i) {
    for (int j = 0; j < nx * ny; ++j) {
      const int dx = i % nx - j % nx, dy = i / nx - j / nx;
      if (i == j || dx * dx + dy * dy > 9) continue;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          const double v = u(rng);
          entries.emplace_back(2 * i + a, 2 * j + b, v);
          row_sum[2 * i + a] += std::abs(v);
        }
    }
  }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, i == zero_diagonal ? 0.0 : row_sum[i] + 1.0);
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

double relative_residual(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (a * x - b).norm() / b.norm();
}

TEST(SparseLu, SolvesAsEigensColumnOrderedLuDoes) {
  const Eigen::SparseMatrix<double> a = grid_matrix(20, 12, 1);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  SparseLu lu;
  lu.analyse(a);
  ASSERT_TRUE(lu.factorize(a));
  const Eigen::VectorXd x = lu.solve(b);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> reference;
  reference.compute(a);
  ASSERT_EQ(reference.info(), Eigen::Success);
  const Eigen::VectorXd x_reference = reference.solve(b);
  // both backward stable on a well-conditioned matrix: round-off of a few hundred operations
  EXPECT_LT(relative_residual(a, x, b), 1e-13);
  EXPECT_LT((x - x_reference).norm() / x_reference.norm(), 1e-12);
}

TEST(SparseLu, RefactorisesNewValuesOnTheAnalysedPattern) {
  const Eigen::SparseMatrix<double> first = grid_matrix(15, 10, 2);
  const Eigen::SparseMatrix<double> second = grid_matrix(15, 10, 3);  // same pattern, new values
  SparseLu lu;
  lu.analyse(first);
  ASSERT_TRUE(lu.same_pattern(second));
  ASSERT_TRUE(lu.factorize(second));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(second.rows());
  // the values must reach their permuted places: a misplaced entry leaves a residual of order one
  EXPECT_LT(relative_residual(second, lu.solve(b), b), 1e-13);
  const Eigen::SparseMatrix<double> other = grid_matrix(15, 11, 2);
  EXPECT_FALSE(lu.same_pattern(other));
  EXPECT_FALSE(lu.factorize(other));
}

TEST(SparseLu, PivotsAwayFromAZeroDiagonal) {
  const Eigen::SparseMatrix<double> a = grid_matrix(12, 8, 4, 37);
  SparseLu lu;
  lu.analyse(a);
  ASSERT_TRUE(lu.factorize(a));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), 1.0, 3.0);
  EXPECT_LT(relative_residual(a, lu.solve(b), b), 1e-12);
}

// The order is applied to rows and columns alike and the diagonal pivots are kept, so the LU
// fills about as a symmetric factorisation in the same order does (L + U about twice L of
// LDL^T). An order applied inverted to the columns fills several times more (Eigen's
// SparseLU with AMDOrdering: 6x on the notched plate's HHT matrix).
TEST(SparseLu, FillsAsTheSymmetricFactorisationInTheSameOrder) {
  const Eigen::SparseMatrix<double> a = grid_matrix(64, 32, 5);
  SparseLu lu;
  lu.analyse(a);
  ASSERT_TRUE(lu.factorize(a));
  const Eigen::SparseMatrix<double> symmetric = 0.5 * (a + Eigen::SparseMatrix<double>(a.transpose()));
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  ldlt.compute(symmetric);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const long symmetric_entries = 2 * ldlt.matrixL().nestedExpression().nonZeros() + a.rows();
  // the supernodal LU stores its dense blocks whole, a little more than the exact fill
  EXPECT_LT(lu.factor_entries(), 1.25 * symmetric_entries);
}

// A strip of 80 x 5 particles whose six end columns are each eliminated onto a rigid body:
// every unknown of an end region reaches every row of that region, as a body's acceleration
// carries the forces on all its particles (as on the flexible slider-crank).
Eigen::SparseMatrix<double> attached_strip() {
  constexpr int nx = 80, ny = 5, region = 6;
  Eigen::SparseMatrix<double> a = grid_matrix(nx, ny, 6);
  std::vector<Eigen::Triplet<double>> block;
  for (int end = 0; end < 2; ++end)
    for (int i = 0; i < region * ny; ++i)
      for (int j = 0; j < region * ny; ++j) {
        const int pi = (i / region) * nx + (end ? nx - 1 - i % region : i % region);
        const int pj = (j / region) * nx + (end ? nx - 1 - j % region : j % region);
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) block.emplace_back(2 * pi + r, 2 * pj + c, 0.01);
      }
  Eigen::SparseMatrix<double> coupling(a.rows(), a.cols());
  coupling.setFromTriplets(block.begin(), block.end());
  a += coupling;
  a.makeCompressed();
  return a;
}

long column_order_entries(const Eigen::SparseMatrix<double>& a) {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(a);
  return lu.nnzL() + lu.nnzU();
}

// Ordered one unknown at a time, the symmetric order filled such regions far more than COLAMD's
// column order with row pivoting (more than 1/0.75 times the entries here; 108,000 against
// 61,000 on the slider-crank); with the unknowns of identical columns ordered as one it fills
// no more.
TEST(SparseLu, FillsCoupledRegionsNoMoreThanTheColumnOrder) {
  const Eigen::SparseMatrix<double> a = attached_strip();
  SparseLu lu;
  lu.analyse(a);
  ASSERT_TRUE(lu.factorize(a));
  EXPECT_LE(lu.factor_entries(), column_order_entries(a));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -2.0, 1.0);
  EXPECT_LT(relative_residual(a, lu.solve(b), b), 1e-13);
  // refactorised on the analysed pattern
  const Eigen::SparseMatrix<double> doubled = 2.0 * a;
  ASSERT_TRUE(lu.factorize(doubled));
  EXPECT_LT(relative_residual(doubled, lu.solve(b), b), 1e-13);
}

}  // namespace
}  // namespace periflex
