// Building a PdBody (src/pd/pd_body_build.cpp): the bond family (partial volumes, both
// directions), notches cut the bonds across them, grids with holes and particles picked by
// position, loads on regions, and a grid beyond the particle limit refused before anything is
// allocated.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "pd/pd_body.h"
#include "pd_test_support.h"
#include <set>
#include <utility>
#include <vector>

namespace periflex {
namespace {

TEST(PdBodyBuild, ANotchLeavesNoBondAcrossItAndKeepsTheOthers) {
  FlexBodyDef def = test::glass_plate(0.02, 0.012, 1e-3);
  // a vertical notch up from the lower edge at x = 0 (between two particle columns) to y = 0
  def.notches.push_back({Vec2(0.0, -0.007), Vec2(0.0, 0.0)});
  auto body = PdBody::build(def, 0);
  const BondStore& b = body->bonds();
  const std::vector<double>& x = body->reference_positions();
  long across_below = 0, across_above = 0;
  for (int i = 0; i < body->particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      const double xi = x[2 * i], yi = x[2 * i + 1], xj = x[2 * j], yj = x[2 * j + 1];
      if (!(xi < 0.0 && xj > 0.0)) continue;
      // where the bond crosses x = 0, by linear interpolation
      const double y_cross = yi + (yj - yi) * (0.0 - xi) / (xj - xi);
      if (y_cross <= 0.0) ++across_below;
      else ++across_above;
    }
  }
  EXPECT_EQ(across_below, 0);
  EXPECT_GT(across_above, 0);
}

TEST(PdBodyBuild, RefusesAGridBeyondTheParticleLimitNamingGridSpacing) {
  FlexBodyDef def = test::glass_plate(10.0, 10.0, 1e-3);  // 1e8 particles
  try {
    PdBody::build(def, 0);
    FAIL() << "a grid of 1e8 particles was built";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid_spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("raise grid_spacing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace periflex

namespace periflex {
namespace {

using test::affine_positions;
using test::box;
using test::centre_particle;
using test::glass_plate;

long row_length(const PdBody& body, int i) { return body.bonds().row[i + 1] - body.bonds().row[i]; }

TEST(PdBonds, InteriorParticleHas28BondsAtHorizonRatio3) {
  // grid points (a, b) != 0 with a^2 + b^2 <= 9: 28 of them
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  def.partial_volume_correction = false;
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(row_length(*body, centre_particle(*body)), 28);
}

TEST(PdBonds, PartialVolumeBandAddsTheRingAtSqrt10) {
  // with the band delta + dx/2 = 3.5 dx the 8 points with a^2 + b^2 = 10 join as partial neighbours
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(row_length(*body, centre_particle(*body)), 36);
}

TEST(PdBonds, EveryBondIsStoredInBothDirectionsWithIdenticalData) {
  auto body = PdBody::build(glass_plate(0.012, 0.008, 1e-3), 0);
  const BondStore& b = body->bonds();
  for (int i = 0; i < b.particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      const auto begin = b.neighbor.begin() + b.row[j], end = b.neighbor.begin() + b.row[j + 1];
      const auto it = std::find(begin, end, i);
      ASSERT_NE(it, end);
      const int64_t back = it - b.neighbor.begin();
      EXPECT_EQ(b.length_class[k], b.length_class[back]);
      EXPECT_EQ(b.coefficient[k], b.coefficient[back]);
    }
  }
}

TEST(PdNotch, RemovesExactlyTheBondsCrossingTheNotch) {
  // notch along y = 0 from the left edge to x = 0.0032 (off the bond crossing points); particles sit at y = +-dx/2, +-3dx/2, ...
  // a bond crosses it when its ends lie on opposite sides and it meets y = 0 at x < 0.003
  const double dx = 1e-3, tip = 0.0032;
  FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  auto intact = PdBody::build(def, 0);
  NotchDef notch;
  notch.p1 = Vec2(-0.011, 0.0);
  notch.p2 = Vec2(tip, 0.0);
  def.notches.push_back(notch);
  auto cut = PdBody::build(def, 0);

  std::vector<std::pair<int, int>> before, after;
  intact->bond_pairs(before, 1u << 30);
  cut->bond_pairs(after, 1u << 30);
  const std::vector<double>& x = intact->reference_positions();
  long expected_removed = 0;
  std::set<std::pair<int, int>> kept(after.begin(), after.end());
  for (const auto& [i, j] : before) {
    const double yi = x[2 * i + 1], yj = x[2 * j + 1];
    bool crosses = false;
    if (yi * yj < 0.0) {
      const double xc = x[2 * i] + (x[2 * j] - x[2 * i]) * (0.0 - yi) / (yj - yi);
      crosses = xc < tip;
    }
    expected_removed += crosses ? 1 : 0;
    EXPECT_EQ(kept.count({i, j}), crosses ? 0u : 1u) << i << " " << j;
  }
  EXPECT_GT(expected_removed, 0);
  EXPECT_EQ(intact->bond_count() - cut->bond_count(), expected_removed);
}

// A notch is a closed segment: one that ends exactly where bonds cross its line (here at x = 0,
// between the particle columns at x = -dx/2 and +dx/2) cuts them, as one reaching a tenth of a
// cell further does; one stopping a tenth of a cell short does not. Before, an exact
// floating-point zero left the bonds through the end point intact.
TEST(PdNotch, ANotchEndingOnABondCutsIt) {
  const double dx = 1e-3;
  const FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  auto bonds_with_tip_at = [&](double tip) {
    FlexBodyDef notched = def;
    NotchDef notch;
    notch.p1 = Vec2(-0.011, 0.0);
    notch.p2 = Vec2(tip, 0.0);
    notched.notches.push_back(notch);
    return PdBody::build(notched, 0)->bond_count();
  };
  // the bonds of the un-notched plate that cross y = 0 exactly at x = 0
  auto intact = PdBody::build(def, 0);
  std::vector<std::pair<int, int>> pairs;
  intact->bond_pairs(pairs, 1u << 30);
  const std::vector<double>& x = intact->reference_positions();
  long through_end = 0;
  for (const auto& [i, j] : pairs) {
    const double yi = x[2 * i + 1], yj = x[2 * j + 1];
    if (yi * yj >= 0.0) continue;
    const double xc = x[2 * i] + (x[2 * j] - x[2 * i]) * (0.0 - yi) / (yj - yi);
    through_end += std::abs(xc) < 1e-9 * dx;
  }
  ASSERT_GT(through_end, 0);
  const long on_end = bonds_with_tip_at(0.0);
  EXPECT_EQ(on_end, bonds_with_tip_at(0.1 * dx));
  EXPECT_EQ(bonds_with_tip_at(-0.1 * dx) - on_end, through_end);
}

// damage = "include_notch": bonds cut by a notch count as broken, so the particles along it start
// damaged (half their weight gone at most: the notch cuts one side); "exclude_notch" (the
// default) leaves them out of the initial weight, and nothing starts damaged.
TEST(PdNotch, DamageCountsNotchBondsOnlyWhenAsked) {
  const double dx = 1e-3;
  FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  NotchDef notch;
  notch.p1 = Vec2(-0.011, 0.0);
  notch.p2 = Vec2(0.0032, 0.0);
  def.notches.push_back(notch);
  std::vector<float> damage;
  PdBody::build(def, 0)->damage(damage);
  EXPECT_EQ(*std::max_element(damage.begin(), damage.end()), 0.0f);

  def.damage = FlexBodyDef::Damage::kIncludeNotch;
  auto body = PdBody::build(def, 0);
  body->damage(damage);
  const std::vector<double>& x = body->reference_positions();
  for (size_t i = 0; i < damage.size(); ++i) {
    const double px = x[2 * i], py = x[2 * i + 1];
    // beside the notch, within the horizon: bonds across it are gone; elsewhere nothing is
    const bool beside = std::abs(py) < 3 * dx && px < 0.0032 + 3 * dx;
    if (std::abs(py) < dx && px < 0.0) {
      EXPECT_GT(damage[i], 0.2f) << px << ", " << py;
      EXPECT_LT(damage[i], 0.5f) << px << ", " << py;
    }
    if (!beside) {
      EXPECT_EQ(damage[i], 0.0f) << px << ", " << py;
    }
  }
}

TEST(PdInput, RefusesHugeGridsWithTheEstimatedCount) {
  FlexBodyDef def = glass_plate(1.0, 1.0, 1e-4);  // 1e8 particles
  def.where.file = "big.toml";
  def.where.line = 12;
  try {
    PdBody::build(def, 0);
    FAIL() << "no refusal";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("100000000"), std::string::npos) << what;
    EXPECT_NE(what.find("big.toml:12"), std::string::npos) << what;
    EXPECT_NE(what.find("grid_spacing"), std::string::npos) << what;
  }
}

TEST(PdInput, WarnsAboutAPoissonRatioBondBasedPdCannotRepresent) {
  FlexBodyDef def = glass_plate(0.01, 0.01, 1e-3);
  def.material.poisson_ratio = 0.22;
  EXPECT_EQ(PdBody::build(def, 0)->warnings().size(), 1u);
  def.material.poisson_ratio = 1.0 / 3.0;
  EXPECT_TRUE(PdBody::build(def, 0)->warnings().empty());
  def.material.plane_strain = true;
  EXPECT_EQ(PdBody::build(def, 0)->warnings().size(), 1u);
}

TEST(PdGrid, BoxWithHoleHasTheExpectedParticleCount) {
  // 20 x 10 cells, a circular hole of radius 2.5 dx at the centre removes the 4 x 4 block minus
  // its corners (12 particles at distance sqrt(0.5^2 + 0.5^2) and sqrt(0.5^2 + 1.5^2) dx)
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3);
  ShapeDef hole;
  hole.kind = ShapeDef::Kind::kCircle;
  hole.radius = 1.7e-3;
  def.holes.push_back(hole);
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(body->particle_count(), 200 - 12);
  EXPECT_NEAR(body->volumes()[0], 1e-9, 1e-21);
  EXPECT_NEAR(body->masses()[0], 2440.0 * 1e-9, 1e-18);
}

TEST(PdLoads, TractionOnAnEdgeRowSumsToTractionTimesEdgeLengthTimesThickness) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3, 2e-3);
  RegionLoadDef load;
  load.kind = RegionLoadDef::Kind::kTraction;
  load.region = box(0.02, 0.001, Vec2(0.0, 0.0045));
  load.fy = TimeFunction::constant(2e6);
  def.loads.push_back(load);
  load.region = box(0.02, 0.002, Vec2(0.0, -0.004));  // two rows: same total force
  load.fy = TimeFunction::constant(-2e6);
  def.loads.push_back(load);
  def.surface_correction = false;
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  double top = 0.0, bottom = 0.0;
  for (int i = 0; i < body->particle_count(); ++i) (q[2 * i + 1] > 0 ? top : bottom) += g[2 * i + 1];
  EXPECT_NEAR(top, 2e6 * 0.02 * 2e-3, 1e-6);
  EXPECT_NEAR(bottom, -2e6 * 0.02 * 2e-3, 1e-6);
}

TEST(PdLoads, PrescribedVelocityBecomesItsDisplacement) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3);
  RegionLoadDef load;
  load.kind = RegionLoadDef::Kind::kPrescribedVelocity;
  load.region = box(0.001, 0.01, Vec2(0.0095, 0.0));
  load.fx = TimeFunction::constant(0.5);
  def.loads.push_back(load);
  auto body = PdBody::build(def, 7);
  const std::vector<PrescribedCoordinate> pcs = body->prescribed_coordinates();
  ASSERT_EQ(pcs.size(), 10u);  // one column of 10 particles, x only
  for (const PrescribedCoordinate& pc : pcs) {
    EXPECT_EQ((pc.coordinate - 7) % 2, 0);
    EXPECT_DOUBLE_EQ(pc.displacement(2.0), 1.0);
    EXPECT_DOUBLE_EQ(pc.reference, body->reference_positions()[pc.coordinate - 7]);
    EXPECT_DOUBLE_EQ(body->initial_velocities()[pc.coordinate - 7], 0.5);
  }
}

TEST(PdGrid, ParticlesInAndNearestParticleSelectByReferencePosition) {
  // a 10 x 6 grid with dx = 1 mm: the box over the right two columns holds 12 particles, all with
  // x > 3 mm; the particle nearest (4.4, -2.4) mm sits at (4.5, -2.5) mm
  auto body = PdBody::build(test::glass_plate(0.01, 0.006, 1e-3), 0);
  const std::vector<int> right = body->particles_in(test::box(0.002, 0.006, Vec2(0.004, 0.0)));
  EXPECT_EQ(right.size(), 12u);
  for (int i : right) EXPECT_GT(body->reference_positions()[2 * i], 0.003);
  const int nearest = body->nearest_particle(Vec2(0.0044, -0.0024));
  EXPECT_NEAR(body->reference_positions()[2 * nearest], 0.0045, 1e-12);
  EXPECT_NEAR(body->reference_positions()[2 * nearest + 1], -0.0025, 1e-12);
}

}  // namespace
}  // namespace periflex
