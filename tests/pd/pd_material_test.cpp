// The material constants (src/pd/pd_material.cpp): partial volumes (the exact area of a
// neighbour's cell inside the horizon disc), the micromodulus and critical stretch against the
// continuum, the influence function, and the critical time step.
#include "pd/pd_material.h"

#include <gtest/gtest.h>

#include <cmath>
#include "pd/pd_body.h"
#include "pd_test_support.h"

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

namespace periflex {
namespace {

using test::glass_plate;

TEST(PdMaterial, MicromodulusReproducesContinuumEnergyOfIsotropicExpansion) {
  // midpoint quadrature of W = 1/4 int_H c s^2 |xi| dV (dV = t r dr dtheta, s = eps) against the
  // classical plane-stress (nu = 1/3) and plane-strain (nu = 1/4) energies; 1e-6: quadrature error
  const double e = 72e9, t = 2e-3, delta = 3e-3, eps = 1e-3;
  for (bool plane_strain : {false, true}) {
    const double c = micromodulus(e, t, delta, plane_strain);
    const int nr = 20000;
    double w = 0.0;
    for (int k = 0; k < nr; ++k) {
      const double r = (k + 0.5) * delta / nr;
      w += 0.25 * c * eps * eps * r * t * r * 2.0 * kPi * (delta / nr);
    }
    const double nu = implied_poisson_ratio(plane_strain);
    const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
    // plane strain: 2 (lambda + mu) eps^2; plane stress: E eps^2 / (1 - nu)
    const double classical = plane_strain ? 2 * (lambda + mu) * eps * eps : e / (1 - nu) * eps * eps;
    EXPECT_NEAR(w / classical, 1.0, 1e-6) << (plane_strain ? "strain" : "stress");
  }
}

TEST(PdMaterial, CriticalStretchReleasesFractureEnergyAcrossACrackLine) {
  // energy of all bonds crossing a straight crack per unit length and thickness, by quadrature
  // over the lower point's depth z, bond length r and angle: must equal G0. 1e-4: quadrature error
  const double e = 72e9, t = 1e-3, delta = 1e-3, g0 = 3.8;
  for (auto influence_kind : {FlexBodyDef::Influence::kConstant, FlexBodyDef::Influence::kConical}) {
    for (bool plane_strain : {false, true}) {
      const double c = micromodulus(e, t, delta, plane_strain);
      const double s0 = critical_stretch_from_energy(g0, e, delta, plane_strain, influence_kind);
      const int nz = 400, nr = 400;
      double per_length = 0.0;
      for (int a = 0; a < nz; ++a) {
        const double z = (a + 0.5) * delta / nz;
        for (int b = 0; b < nr; ++b) {
          const double r = z + (b + 0.5) * (delta - z) / nr;
          const double w = influence(influence_kind, r, delta);
          const double bond = 0.5 * c * w * s0 * s0 * r;           // energy per unit volume^2
          per_length += bond * (2.0 * std::acos(z / r)) * t * r * ((delta - z) / nr) * t * (delta / nz);
        }
      }
      EXPECT_NEAR(per_length / t / g0, 1.0, 1e-3) << plane_strain << " " << static_cast<int>(influence_kind);
    }
  }
}

TEST(PdStableStep, CriticalStepMatchesSillingAskariForAnInteriorParticle) {
  // without corrections every bond has C = c: dt = sqrt(2 rho / (c V sum_j 1/|xi_j|)) over the
  // 28 lattice neighbours of an interior particle (which has the most bonds, hence the minimum)
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  def.partial_volume_correction = false;
  def.surface_correction = false;
  auto body = PdBody::build(def, 0);
  double sum_inv = 0.0;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b)
      if ((a || b) && a * a + b * b <= 9) sum_inv += 1.0 / (1e-3 * std::sqrt(a * a + b * b));
  const double c = micromodulus(72e9, 1e-3, 3e-3, false), v = 1e-6 * 1e-3;
  const double expected = std::sqrt(2.0 * 2440.0 / (c * v * sum_inv));
  // 1e-7: bond stiffnesses are stored in single precision (relative rounding up to 6e-8 each)
  EXPECT_NEAR(body->critical_time_step() / expected, 1.0, 1e-7);
}

TEST(PdMaterial, ConicalInfluenceKeepsTheBulkStiffness) {
  // midpoint quadrature of int_0^delta w(r) r^2 dr against delta^3 / 3 (the constant function's
  // value), which is what the isotropic energy and hence the bulk modulus depend on; 1e-6:
  // quadrature error
  const double delta = 2e-3;
  const int steps = 100000;
  double conical = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double r = (k + 0.5) * delta / steps;
    conical += influence(FlexBodyDef::Influence::kConical, r, delta) * r * r * delta / steps;
  }
  EXPECT_NEAR(conical / (delta * delta * delta / 3.0), 1.0, 1e-6);
  EXPECT_EQ(influence(FlexBodyDef::Influence::kConical, 1.01 * delta, delta), 0.0);
}

}  // namespace
}  // namespace periflex
