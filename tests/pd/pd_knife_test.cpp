// The knife (PdBody::cut_bonds): the bonds a segment separates are broken between steps by the
// same test a scene's notch makes at set-up, both stored directions at once, at the positions
// the caller sees, with the strain energy they held booked.
#include <gtest/gtest.h>

#include <set>

#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

using test::affine_positions;
using test::glass_plate;

Eigen::VectorXd reference_q(const PdBody& body) {
  const std::vector<double>& x = body.reference_positions();
  return Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
}

std::set<std::pair<int, int>> intact_pairs(const PdBody& body) {
  std::vector<std::pair<int, int>> pairs;
  body.bond_pairs(pairs, 1u << 30);
  return {pairs.begin(), pairs.end()};
}

TEST(PdKnife, CutsTheBondsANotchRemovesAtSetUp) {
  // a slanted segment from the left edge into the plate, off the grid's symmetry lines
  const double dx = 1e-3;
  FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  auto knifed = PdBody::build(def, 0);
  NotchDef notch;
  notch.p1 = Vec2(-0.0113, -0.0021);
  notch.p2 = Vec2(0.0037, 0.0017);
  def.notches.push_back(notch);
  auto notched = PdBody::build(def, 0);

  const FractureUpdate update = knifed->cut_bonds(reference_q(*knifed), {}, notch.p1, notch.p2);
  EXPECT_GT(update.bonds_broken, 0);
  EXPECT_EQ(update.bonds_broken, knifed->bond_count() - notched->bond_count());
  EXPECT_EQ(knifed->broken_bond_count(), update.bonds_broken);
  EXPECT_EQ(intact_pairs(*knifed), intact_pairs(*notched));
  // both stored directions of every pair: as many broken in rows as pairs cut, twice
  const BondState& b = knifed->bond_state();
  long directed = 0;
  for (size_t k = 0; k < b.broken.size(); ++k) {
    directed += b.broken[k];
    if (b.broken[k]) {
      EXPECT_EQ(b.stiffness[k], 0.0f);
    }
  }
  EXPECT_EQ(directed, 2 * update.bonds_broken);
  // undeformed: no energy to release (but round-off); the same cut again finds nothing left
  EXPECT_NEAR(update.energy_released, 0.0, 1e-20);
  EXPECT_EQ(knifed->cut_bonds(reference_q(*knifed), {}, notch.p1, notch.p2).bonds_broken, 0);
}

TEST(PdKnife, TestsThePositionsTheCallerSees) {
  // the body drawn 1 m to the right: a segment there cuts as one through the body itself
  const double dx = 1e-3;
  auto shown = PdBody::build(glass_plate(0.02, 0.012, dx), 0);
  auto plain = PdBody::build(glass_plate(0.02, 0.012, dx), 0);
  std::vector<double> drawn = shown->reference_positions();
  for (size_t i = 0; i < drawn.size(); i += 2) drawn[i] += 1.0;
  const Vec2 a(0.0002, -0.007), b(0.0002, 0.002), shift(1.0, 0.0);
  const long at_drawn = shown->cut_bonds(reference_q(*shown), drawn, a + shift, b + shift).bonds_broken;
  const long at_q = plain->cut_bonds(reference_q(*plain), {}, a, b).bonds_broken;
  EXPECT_GT(at_q, 0);
  EXPECT_EQ(at_drawn, at_q);
  EXPECT_EQ(intact_pairs(*shown), intact_pairs(*plain));
}

// A cut right across a stretched plate: the halves hold no bond between them (moved apart
// rigidly they store no energy), and the energy the cut bonds held is what the plate lost.
TEST(PdKnife, ACutAcrossSeparatesTheHalvesAndBooksTheirEnergy) {
  for (const bool state_based : {false, true}) {
    SCOPED_TRACE(state_based ? "state-based" : "bond-based");
    FlexBodyDef def = glass_plate(0.02, 0.012, 1e-3);
    if (state_based) {
      def.material.model = PdMaterialDef::Model::kStateBased;
      def.material.poisson_ratio = 0.25;
    }
    auto body = PdBody::build(def, 0);
    Eigen::Matrix2d h;
    h << 1e-4, 0.0, 0.0, -2e-5;
    const Eigen::VectorXd stretched = affine_positions(*body, h);
    const double before = body->potential_energy(stretched);
    const FractureUpdate update = body->cut_bonds(stretched, {}, Vec2(0.0003, -0.01), Vec2(0.0003, 0.01));
    EXPECT_GT(update.bonds_broken, 0);
    EXPECT_GT(update.energy_released, 0.0);
    EXPECT_NEAR(update.energy_released, before - body->potential_energy(stretched), 1e-12 * before);
    // the right half moved 5 mm away, the left one kept: no bond is stretched
    Eigen::VectorXd apart = reference_q(*body);
    const std::vector<double>& x = body->reference_positions();
    for (size_t i = 0; i < x.size(); i += 2)
      if (x[i] > 0.0003) apart[static_cast<Eigen::Index>(i)] += 5e-3;
    EXPECT_NEAR(body->potential_energy(apart), 0.0, 1e-12 * before);
  }
}

}  // namespace
}  // namespace periflex
