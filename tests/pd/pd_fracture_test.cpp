// Breaking bonds (src/pd/pd_fracture.cpp): the break pass after a step breaks exactly the bonds
// past s0 and books the energy they held; breaks made inside force evaluations are handed over once.
#include <gtest/gtest.h>

#include <cmath>

#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

TEST(PdFracture, TheBreakPassBreaksTheBondsPastS0AndBooksTheirEnergy) {
  test::SerialScope serial;
  auto body = PdBody::build(test::glass_plate(0.012, 0.008, 1e-3), 0);
  body->set_break_timing(PdBody::BreakTiming::kAfterStep);
  const double s0 = body->critical_stretch();
  // stretched along x by 1.2 s0: the bonds along x and near it pass s0, the steep ones do not
  Eigen::Matrix2d h;
  h << 1.2 * s0, 0.0, 0.0, 0.0;
  const Eigen::VectorXd q = test::affine_positions(*body, h);
  // what should break, from the geometry: every pair whose stretch exceeds s0, and its k |xi| s^2 / 2
  const BondStore& b = body->bonds();
  long expected_pairs = 0;
  double expected_energy = 0.0;
  for (int i = 0; i < body->particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      if (j < i) continue;
      const double dx = q[2 * j] - q[2 * i], dy = q[2 * j + 1] - q[2 * i + 1];
      const double s = std::sqrt(dx * dx + dy * dy) * b.inv_length(k) - 1.0;
      if (s <= s0) continue;
      ++expected_pairs;
      expected_energy += 0.5 * double(b.coefficient[k]) * s * s / b.inv_length(k);
    }
  }
  ASSERT_GT(expected_pairs, 0);
  const FractureUpdate update = body->update_fracture(q);
  EXPECT_EQ(update.bonds_broken, expected_pairs);
  EXPECT_EQ(body->broken_bond_count(), expected_pairs);
  EXPECT_NEAR(update.energy_released, expected_energy, 1e-12 * expected_energy);
  EXPECT_TRUE(update.forces_stale);
  // nothing is left past s0: a second pass breaks nothing
  EXPECT_EQ(body->update_fracture(q).bonds_broken, 0);
}

TEST(PdFracture, BreaksInsideEvaluationsAreHandedOverOnce) {
  test::SerialScope serial;
  auto body = PdBody::build(test::glass_plate(0.012, 0.008, 1e-3), 0);
  ASSERT_TRUE(body->breaks_in_evaluation());
  Eigen::Matrix2d h;
  h << 1.2 * body->critical_stretch(), 0.0, 0.0, 0.0;
  const Eigen::VectorXd q = test::affine_positions(*body, h);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  const FractureUpdate first = body->take_evaluation_breaks();
  EXPECT_GT(first.bonds_broken, 0);
  EXPECT_GT(first.energy_released, 0.0);
  EXPECT_EQ(body->broken_bond_count(), first.bonds_broken);
  const FractureUpdate second = body->take_evaluation_breaks();
  EXPECT_EQ(second.bonds_broken, 0);
  EXPECT_EQ(second.energy_released, 0.0);
}

}  // namespace
}  // namespace periflex

namespace periflex {
namespace {

using test::affine_positions;
using test::box;
using test::glass_plate;

TEST(PdDamage, BrokenBondsRaiseDamageAndReleaseTheirEnergy) {
  // stretch a strip uniformly past s0: every breakable bond goes, damage -> 1, and the released
  // energy equals the strain energy held just before (1e-12 relative: same sums)
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  auto body = PdBody::build(def, 0);
  Eigen::Matrix2d h = Eigen::Matrix2d::Identity() * 2e-3;
  const Eigen::VectorXd q = affine_positions(*body, h);
  const double stored = body->potential_energy(q);
  const FractureUpdate up = body->update_fracture(q);
  EXPECT_EQ(up.bonds_broken, body->bond_count());
  EXPECT_NEAR(up.energy_released / stored, 1.0, 1e-12);
  std::vector<float> d;
  body->damage(d);
  for (float v : d) EXPECT_FLOAT_EQ(v, 1.0f);
  EXPECT_EQ(body->potential_energy(q), 0.0);
}

TEST(PdDamage, NoFailRegionKeepsItsBonds) {
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  def.no_fail_regions.push_back(box(0.004, 0.004, Vec2(0.008, 0.0)));
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = affine_positions(*body, Eigen::Matrix2d::Identity() * 2e-3);
  body->update_fracture(q);
  std::vector<float> d;
  body->damage(d);
  const int inside = body->nearest_particle(Vec2(0.0085, 0.0005));
  const int outside = body->nearest_particle(Vec2(-0.008, 0.0));
  EXPECT_EQ(d[inside], 0.0f);
  EXPECT_EQ(d[outside], 1.0f);
}

TEST(PdDamage, FractureOffNeverBreaks) {
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  def.fracture = false;
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = affine_positions(*body, Eigen::Matrix2d::Identity() * 2e-3);
  EXPECT_EQ(body->update_fracture(q).bonds_broken, 0);
  EXPECT_EQ(body->broken_bond_count(), 0);
}

}  // namespace
}  // namespace periflex
