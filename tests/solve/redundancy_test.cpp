// Dependent-row detection on Jacobians with the structure the solver meets: many rows with a
// column of their own (attached particles) around a few rows that may depend on each other.
#include <gtest/gtest.h>

#include <cmath>

#include "core/cpu_time.h"
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


// Two bodies (coordinates 0..2 and 3..5) that both hold the same n particles (a plate held
// whole by two grips), body 0 pinned to the ground and turned by a driver, body 1 optionally
// driven too: rows 2 per particle and body, then the pin (2), the driver(s). The particles are
// on a grid over 0.1 m x 0.04 m; the bodies' origins at the two upper corners.
struct SharedPlate {
  Eigen::SparseMatrix<double> j;
  Eigen::VectorXd rates;           // Phi_t: what the drivers ask of the velocities
  std::vector<char> eliminable;    // the particle columns
  int particles = 0, first_driver = 0;
};

SharedPlate shared_plate(int particles, bool drive_both, double rate0 = -6.0, double rate1 = 6.0) {
  SharedPlate plate;
  plate.particles = particles;
  const int n = 6 + 2 * particles;
  std::vector<Eigen::Triplet<double>> t;
  const double origin_x[2] = {-0.05, 0.05}, origin_y = 0.02;
  const int columns = 100;
  int row = 0;
  for (int body = 0; body < 2; ++body) {
    for (int p = 0; p < particles; ++p) {
      const double x = -0.05 + 0.1 * (p % columns) / (columns - 1), y = -0.02 + 0.04 * (p / columns) / (particles / columns);
      const double sx = x - origin_x[body], sy = y - origin_y;
      // r_v + A s - x_p: d/d(x, y, phi) = [1 0 -sy; 0 1 sx] at phi = 0
      t.emplace_back(row, 3 * body, 1.0);
      t.emplace_back(row, 3 * body + 2, -sy);
      t.emplace_back(row, 6 + 2 * p, -1.0);
      ++row;
      t.emplace_back(row, 3 * body + 1, 1.0);
      t.emplace_back(row, 3 * body + 2, sx);
      t.emplace_back(row, 6 + 2 * p + 1, -1.0);
      ++row;
    }
  }
  t.emplace_back(row++, 0, 1.0);  // pin of body 0
  t.emplace_back(row++, 1, 1.0);
  plate.first_driver = row;
  t.emplace_back(row++, 2, 1.0);  // driver of body 0's angle
  if (drive_both) t.emplace_back(row++, 5, 1.0);
  plate.j.resize(row, n);
  plate.j.setFromTriplets(t.begin(), t.end());
  plate.rates = Eigen::VectorXd::Zero(row);
  plate.rates[plate.first_driver] = -rate0;
  if (drive_both) plate.rates[plate.first_driver + 1] = -rate1;
  plate.eliminable.assign(n, 0);
  for (int c = 6; c < n; ++c) plate.eliminable[c] = 1;
  return plate;
}

TEST(Redundancy, TwoBodiesHoldingTheSameParticlesLeaveThreeRowsThatTieThem) {
  // rank: 2 per particle, and the 6 body coordinates fixed (pin, driver, and the weld the
  // shared particles make): of 4n + 3 rows, 2n - 3 depend on the others
  const SharedPlate plate = shared_plate(200, false);
  RowAnalysisOptions options;
  options.eliminable = plate.eliminable;
  options.rhs = &plate.rates;
  const RowDependence found = find_dependent_rows(plate.j, options);
  EXPECT_EQ(found.dependent.size(), static_cast<size_t>(2 * plate.particles - 3));
  EXPECT_TRUE(found.conflicting.empty());
  // the same answer as a dense rank-revealing QR of the whole matrix
  const Eigen::MatrixXd dense = Eigen::MatrixXd(plate.j).transpose();
  EXPECT_EQ(column_rank(dense), plate.j.rows() - static_cast<int>(found.dependent.size()));
  // the rows kept are independent: the kept submatrix has full row rank
  std::vector<char> dropped(plate.j.rows(), 0);
  for (int r : found.dependent) dropped[r] = 1;
  Eigen::MatrixXd kept(plate.j.cols(), plate.j.rows() - static_cast<int>(found.dependent.size()));
  for (int r = 0, k = 0; r < plate.j.rows(); ++r) {
    if (!dropped[r]) kept.col(k++) = dense.col(r);
  }
  EXPECT_EQ(column_rank(kept), kept.cols());
}

TEST(Redundancy, DriversThatContradictTheSharedParticlesAreReported) {
  RowAnalysisOptions options;
  // body 1 driven the other way: the weld forbids it
  const SharedPlate opposite = shared_plate(400, true, -6.0, 6.0);
  options.eliminable = opposite.eliminable;
  options.rhs = &opposite.rates;
  const RowDependence conflict = find_dependent_rows(opposite.j, options);
  ASSERT_FALSE(conflict.conflicting.empty());
  const auto& rows = conflict.conflicting;
  EXPECT_TRUE(std::binary_search(rows.begin(), rows.end(), opposite.first_driver) ||
              std::binary_search(rows.begin(), rows.end(), opposite.first_driver + 1));
  // both driven alike: redundant but consistent
  const SharedPlate alike = shared_plate(400, true, -6.0, -6.0);
  options.rhs = &alike.rates;
  const RowDependence consistent = find_dependent_rows(alike.j, options);
  EXPECT_TRUE(consistent.conflicting.empty());
  EXPECT_EQ(consistent.dependent.size(), static_cast<size_t>(2 * alike.particles - 2));
}

TEST(Redundancy, SharedParticlesAnalysisGrowsAboutLinearly) {
  // 16 times the particles in well under 100 times the time (a general sparse QR of the
  // same matrix grew as n^2.5: 1000 times)
  auto seconds_for = [](int particles) {
    const SharedPlate plate = shared_plate(particles, false);
    RowAnalysisOptions options;
    options.eliminable = plate.eliminable;
    // processor time of this thread: what other programs on the machine take does not count
    const double start = thread_cpu_seconds();
    const RowDependence found = find_dependent_rows(plate.j, options);
    const double s = thread_cpu_seconds() - start;
    EXPECT_EQ(found.dependent.size(), static_cast<size_t>(2 * particles - 3));
    return s;
  };
  // the least of three runs each (caches shared with other programs)
  double small = 1e9, large = 1e9;
  for (int k = 0; k < 3; ++k) {
    small = std::min(small, std::max(seconds_for(4000), 1e-3));
    large = std::min(large, seconds_for(64000));
  }
  std::printf("4000 particles: %.4f s, 64000: %.4f s (ratio %.1f)\n", small, large, large / small);
  EXPECT_LT(large, 100.0 * small);
}

}  // namespace
}  // namespace periflex
