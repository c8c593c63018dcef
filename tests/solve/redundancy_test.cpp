// Dependent-row detection on Jacobians with the structure the solver meets: many rows with a
// column of their own (attached particles) around a few rows that may depend on each other.
#include <gtest/gtest.h>

#include "solve/redundancy.h"

namespace periflex {
namespace {

Eigen::SparseMatrix<double> from(int rows, int cols, const std::vector<Eigen::Triplet<double>>& t) {
  Eigen::SparseMatrix<double> j(rows, cols);
  j.setFromTriplets(t.begin(), t.end());
  return j;
}

TEST(Redundancy, DuplicatedPinAmongAttachedParticlesIsTheOnlyDependentPair) {
  // body coordinates 0..2; particles 3..; rows: 2 per particle, then a pin (2 rows) twice
  const int particles = 400;
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  for (int p = 0; p < particles; ++p) {
    for (int k = 0; k < 2; ++k, ++row) {
      t.emplace_back(row, k, 1.0);
      t.emplace_back(row, 2, 0.01 * (p % 13) - 0.05);
      t.emplace_back(row, 3 + 2 * p + k, -1.0);
    }
  }
  for (int copy = 0; copy < 2; ++copy) {
    for (int k = 0; k < 2; ++k, ++row) t.emplace_back(row, k, 1.0);
  }
  const auto dependent = dependent_rows(from(row, 3 + 2 * particles, t));
  ASSERT_EQ(dependent.size(), 2u);
  // one of the two copies of each pin row
  for (int r : dependent) EXPECT_GE(r, 2 * particles);
}

TEST(Redundancy, IndependentRowsAreKept) {
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}, {0, 1, 2.0}, {1, 1, 1.0}, {2, 0, 1.0}, {2, 2, 1.0}};
  EXPECT_TRUE(dependent_rows(from(3, 3, t)).empty());
  // the third row made the sum of the first two: exactly one dependent
  std::vector<Eigen::Triplet<double>> u = {{0, 0, 1.0}, {0, 1, 2.0}, {1, 1, 1.0}, {2, 0, 1.0}, {2, 1, 3.0}};
  EXPECT_EQ(dependent_rows(from(3, 3, u)).size(), 1u);
}

}  // namespace
}  // namespace periflex
