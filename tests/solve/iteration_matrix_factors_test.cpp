// The factors of an implicit integrator's iteration matrix, on matrices shaped like HHT's on a
// particle grid with grips: S = I + M^-1 c K on the free particles (K symmetric, masses
// unequal), rows of gripped particles that read only the grips' own columns, free rows that read
// the grips. Each solution is checked against Eigen's column-ordered sparse LU of the same S; the
// path taken (the free block by Cholesky, or S whole by LU) against what the matrix allows.
#include <gtest/gtest.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <random>
#include <vector>

#include "solve/iteration_matrix_factors.h"

namespace periflex {
namespace {

struct GripMatrix {
  Eigen::SparseMatrix<double> s;
  Eigen::VectorXd free_mass;  // 0 on the gripped particles' coordinates
};

// An nx x ny grid, particles within three spacings coupled by symmetric 2x2 blocks of a
// positive semi-definite stiffness; the first `gripped` columns of the grid are gripped.
// `skew` adds that much unsymmetric noise to the free block (relative), `read_free` makes one
// gripped row read a free column, `soften` makes the stiffness indefinite; `step` scales K.
GripMatrix grip_matrix(int nx, int ny, unsigned seed, int gripped, double skew = 0.0, bool read_free = false,
                       bool soften = false, double step = 2.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  const int particles = nx * ny, n = 2 * particles;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < particles; ++i)
    for (int j = i + 1; j < particles; ++j) {
      const int dx = j % nx - i % nx, dy = j / nx - i / nx;
      if (dx * dx + dy * dy > 9) continue;
      // a bond along (dx, dy): stiffness c e e^T between the two particles
      const Eigen::Vector2d e = Eigen::Vector2d(dx, dy).normalized();
      const Eigen::Matrix2d block = u(rng) * e * e.transpose();
      k.block<2, 2>(2 * i, 2 * i) += block;
      k.block<2, 2>(2 * j, 2 * j) += block;
      k.block<2, 2>(2 * i, 2 * j) -= block;
      k.block<2, 2>(2 * j, 2 * i) -= block;
    }
  if (soften) k -= 40.0 * Eigen::MatrixXd::Identity(n, n);
  GripMatrix g;
  g.free_mass = Eigen::VectorXd::Zero(n);
  std::vector<char> is_gripped(n, 0);
  for (int p = 0; p < particles; ++p) {
    const bool grip = p % nx < gripped;
    const double m = u(rng);
    for (int a = 0; a < 2; ++a) {
      is_gripped[2 * p + a] = grip;
      if (!grip) g.free_mass[2 * p + a] = m;
    }
  }
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    if (is_gripped[i]) {
      // a gripped coordinate: its own diagonal and its grip's first coordinate
      entries.emplace_back(i, i, 1.0);
      if (i != 0) entries.emplace_back(i, 0, 0.3);
      continue;
    }
    for (int j = 0; j < n; ++j) {
      if (k(i, j) == 0.0 && i != j) continue;
      double v = (i == j ? 1.0 : 0.0) + step * k(i, j) / g.free_mass[i];
      if (i != j && !is_gripped[j]) v *= 1.0 + skew * noise(rng);
      entries.emplace_back(i, j, v);
    }
  }
  if (read_free) entries.emplace_back(0, n - 1, 0.2);
  g.s.resize(n, n);
  g.s.setFromTriplets(entries.begin(), entries.end());
  g.s.makeCompressed();
  return g;
}

// The solution of S x = b against Eigen's LU, relative to its size.
double solution_error(IterationMatrixFactors& factors, const Eigen::SparseMatrix<double>& s) {
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(s.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = factors.solve(b);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> reference;
  reference.compute(s);
  const Eigen::VectorXd expected = reference.solve(b);
  return (x - expected).norm() / expected.norm();
}

// Analyses and factorises S with the given free masses; the path taken, and the solution's
// error against Eigen's LU.
struct Outcome {
  bool factorised, split;
  double error;
};
Outcome factorise(const Eigen::SparseMatrix<double>& s, const Eigen::VectorXd& free_mass) {
  IterationMatrixFactors factors;
  factors.analyse(s, free_mass);
  const bool factorised = factors.factorize(s);
  return {factorised, factors.split(), factorised ? solution_error(factors, s) : 1.0};
}

TEST(IterationMatrixFactors, GrippedGridTakesTheFreeBlockByCholesky) {
  const GripMatrix g = grip_matrix(14, 9, 1, 2);
  const Outcome o = factorise(g.s, g.free_mass);
  ASSERT_TRUE(o.factorised);
  EXPECT_TRUE(o.split);
  EXPECT_LT(o.error, 1e-12);
}

TEST(IterationMatrixFactors, NewValuesOnTheSamePatternAreFactorisedAgain) {
  const GripMatrix first = grip_matrix(12, 8, 2, 1);
  const GripMatrix second = grip_matrix(12, 8, 2, 1, 0.0, false, false, 7.0);  // another step size
  IterationMatrixFactors factors;
  factors.analyse(first.s, first.free_mass);
  ASSERT_TRUE(factors.factorize(first.s));
  ASSERT_TRUE(factors.same_pattern(second.s));
  ASSERT_TRUE(factors.factorize(second.s));
  EXPECT_TRUE(factors.split());
  EXPECT_LT(solution_error(factors, second.s), 1e-12);
}

// A free block symmetric to finite-difference noise is averaged: the solution moves by about
// that noise, not more.
TEST(IterationMatrixFactors, NoiseBelowTheToleranceIsAveragedAway) {
  const GripMatrix g = grip_matrix(12, 8, 4, 2, 1e-8);
  const Outcome o = factorise(g.s, g.free_mass);
  ASSERT_TRUE(o.factorised);
  EXPECT_TRUE(o.split);
  EXPECT_LT(o.error, 1e-6);
}

TEST(IterationMatrixFactors, UnsymmetricFreeBlockIsFactorisedWhole) {
  const GripMatrix g = grip_matrix(12, 8, 5, 2, 0.1);
  IterationMatrixFactors factors;
  factors.analyse(g.s, g.free_mass);
  ASSERT_TRUE(factors.factorize(g.s));
  EXPECT_FALSE(factors.split());
  EXPECT_LT(solution_error(factors, g.s), 1e-12);
  // and stays so for the pattern, even for symmetric values
  const GripMatrix symmetric = grip_matrix(12, 8, 5, 2);
  ASSERT_TRUE(factors.factorize(symmetric.s));
  EXPECT_FALSE(factors.split());
  EXPECT_LT(solution_error(factors, symmetric.s), 1e-12);
}

TEST(IterationMatrixFactors, IndefiniteFreeBlockIsFactorisedWhole) {
  const GripMatrix g = grip_matrix(10, 8, 6, 2, 0.0, false, true);
  const Outcome o = factorise(g.s, g.free_mass);
  ASSERT_TRUE(o.factorised);
  EXPECT_FALSE(o.split);
  EXPECT_LT(o.error, 1e-10);
}

TEST(IterationMatrixFactors, ConstrainedRowReadingAFreeCoordinateIsFactorisedWhole) {
  const GripMatrix g = grip_matrix(10, 8, 7, 2, 0.0, true);
  const Outcome o = factorise(g.s, g.free_mass);
  ASSERT_TRUE(o.factorised);
  EXPECT_FALSE(o.split);
  EXPECT_LT(o.error, 1e-12);
}

TEST(IterationMatrixFactors, NoGripsAndNoMassesBothWork) {
  const GripMatrix free_grid = grip_matrix(10, 8, 8, 0);
  const Outcome split = factorise(free_grid.s, free_grid.free_mass);
  ASSERT_TRUE(split.factorised);
  EXPECT_TRUE(split.split);
  EXPECT_LT(split.error, 1e-12);
  // a system that cannot tell its free masses: S whole
  const Outcome whole = factorise(free_grid.s, Eigen::VectorXd());
  ASSERT_TRUE(whole.factorised);
  EXPECT_FALSE(whole.split);
  EXPECT_LT(whole.error, 1e-12);
}

TEST(IterationMatrixFactors, AnotherPatternIsRefused) {
  const GripMatrix g = grip_matrix(10, 8, 9, 2);
  const GripMatrix other = grip_matrix(11, 8, 9, 2);
  IterationMatrixFactors factors;
  factors.analyse(g.s, g.free_mass);
  EXPECT_FALSE(factors.same_pattern(other.s));
  EXPECT_FALSE(factors.factorize(other.s));
}

}  // namespace
}  // namespace periflex
