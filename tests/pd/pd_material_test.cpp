// Partial volumes: the exact area of a neighbour's cell inside the horizon disc.
#include "pd/pd_material.h"

#include <gtest/gtest.h>

#include <cmath>

namespace periflex {
namespace {

// The cells of the grid tile the plane, so their fractions inside the disc add up to its area
// pi m^2: an independent check of every cell at once (a quadrature of the chords was off by
// about 1e-5 of the area here).
TEST(PartialVolume, CellFractionsAddUpToTheDiscArea) {
  for (double m : {1.5, 2.5, 3.0, 3.7, 15.0}) {
    const int reach = static_cast<int>(std::ceil(m)) + 1;
    double sum = 0.0;
    for (int a = -reach; a <= reach; ++a)
      for (int b = -reach; b <= reach; ++b) sum += cell_fraction_in_disc(a, b, m);
    // round-off of a few hundred terms of size 1
    EXPECT_NEAR(sum, kPi * m * m, 1e-12 * kPi * m * m) << "m = " << m;
  }
}

// The disc is symmetric under swapping and mirroring the axes; so are the fractions, to
// round-off (the midpoint rule across x alone made (3, 0) 6e-5 larger than (0, 3) at m = 3).
TEST(PartialVolume, FractionsAreSymmetric) {
  for (double m : {2.0, 3.0, 3.5, 7.25}) {
    const int reach = static_cast<int>(std::ceil(m)) + 1;
    // a fraction is the difference of four corner areas of size up to m^2: their round-off
    const double tolerance = 8 * 2.2e-16 * m * m;
    for (int a = 0; a <= reach; ++a)
      for (int b = 0; b <= reach; ++b) {
        const double f = cell_fraction_in_disc(a, b, m);
        EXPECT_NEAR(f, cell_fraction_in_disc(b, a, m), tolerance) << a << ", " << b << ", m = " << m;
        EXPECT_NEAR(f, cell_fraction_in_disc(-a, b, m), tolerance);
        EXPECT_NEAR(f, cell_fraction_in_disc(a, -b, m), tolerance);
      }
  }
}

// Against a fine two-dimensional midpoint rule (2000 x 2000 points per cell; its error at the
// disc's edge is below 1e-6 of the cell), computed here independently of the closed form.
TEST(PartialVolume, MatchesAFineQuadratureOfTheCell) {
  const double m = 3.0;
  constexpr int kPoints = 2000;
  for (int a = 0; a <= 4; ++a)
    for (int b = 0; b <= a; ++b) {
      long inside = 0;
      for (int i = 0; i < kPoints; ++i) {
        const double x = a - 0.5 + (i + 0.5) / kPoints;
        for (int j = 0; j < kPoints; ++j) {
          const double y = b - 0.5 + (j + 0.5) / kPoints;
          inside += x * x + y * y <= m * m;
        }
      }
      const double fine = static_cast<double>(inside) / (double(kPoints) * kPoints);
      EXPECT_NEAR(cell_fraction_in_disc(a, b, m), fine, 1e-5) << a << ", " << b;
    }
}

TEST(PartialVolume, WholeAndEmptyCells) {
  EXPECT_DOUBLE_EQ(cell_fraction_in_disc(0, 0, 3.0), 1.0);
  EXPECT_DOUBLE_EQ(cell_fraction_in_disc(2, 1, 3.0), 1.0);  // farthest corner at sqrt(2.5^2 + 1.5^2) < 3
  EXPECT_DOUBLE_EQ(cell_fraction_in_disc(4, 0, 3.0), 0.0);  // nearest edge at 3.5
  EXPECT_DOUBLE_EQ(cell_fraction_in_disc(3, 3, 3.0), 0.0);  // nearest corner at 2.5 sqrt(2) > 3
}

}  // namespace
}  // namespace periflex
