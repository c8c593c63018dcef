// The live bonds (pd/bond_state.h) against the model's store: breaking writes the state alone, and
// a restore sets the state from the saved bits and the store's coefficients, whatever broke
// between the save and the restore.
#include "pd/bond_state.h"

#include <gtest/gtest.h>

#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

using test::affine_positions;
using test::glass_plate;

// Breaks every stored direction k with k % every == rest (both arrays, as a break pass does).
void break_some(BondState& live, int64_t every, int64_t rest) {
  for (int64_t k = 0; k < static_cast<int64_t>(live.broken.size()); ++k)
    if (k % every == rest) live.break_bond(k);
}

TEST(BondState, RestoreGivesTheSavedStateWhateverBrokeSince) {
  auto body = PdBody::build(glass_plate(0.02, 0.01, 1e-3), 0);
  const BondStore& bonds = body->bonds();
  // the last word of bits is a partial one
  ASSERT_NE(bonds.directed_count() % 64, 0);
  BondState live = BondState::intact(bonds);
  EXPECT_EQ(live.stiffness, bonds.coefficient);
  const BondState intact = live;
  std::vector<uint64_t> none, some, more;
  live.save_bits(none);
  break_some(live, 7, 3);
  const BondState after_some = live;
  live.save_bits(some);
  break_some(live, 5, 1);
  // a bond an evaluation left out and nobody settled yet (flag 2) counts as broken when saved
  live.broken[2] = 2;
  live.stiffness[2] = 0.0f;
  BondState after_more = live;
  live.save_bits(more);
  after_more.broken[2] = 1;

  // back to an earlier state heals, forward to a later one breaks, and to the start is intact
  live.restore_bits(bonds, some);
  EXPECT_EQ(live.broken, after_some.broken);
  EXPECT_EQ(live.stiffness, after_some.stiffness);
  live.restore_bits(bonds, more);
  EXPECT_EQ(live.broken, after_more.broken);
  EXPECT_EQ(live.stiffness, after_more.stiffness);
  live.restore_bits(bonds, none);
  EXPECT_EQ(live.broken, intact.broken);
  EXPECT_EQ(live.stiffness, intact.stiffness);
  // and the bits say exactly which directions are broken
  long set = 0;
  for (uint64_t word : some) set += __builtin_popcountll(word);
  long broken = 0;
  for (uint8_t flag : after_some.broken) broken += flag;
  EXPECT_EQ(set, broken);
}

// A run that breaks bonds under load, the knife and a restore change the body's live state and
// never its store: topology and coefficients stay the bits the build made.
TEST(BondState, BreakingCuttingAndRestoringLeaveTheModelsStoreAsBuilt) {
  auto body = PdBody::build(glass_plate(0.02, 0.01, 5e-4), 0);
  const BondStore built = body->bonds();
  FlexState start;
  body->save_state(start);
  // stretched to twice s0 along x: bonds break in the evaluation and in the break pass
  Eigen::Matrix2d h = Eigen::Matrix2d::Zero();
  h(0, 0) = 2.0 * body->critical_stretch();
  const Eigen::VectorXd q = affine_positions(*body, h);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  body->update_fracture(q);
  body->cut_bonds(q, {}, Vec2(-0.011, 0.0), Vec2(0.011, 0.0));
  EXPECT_GT(body->broken_bond_count(), 0);
  long zeroed = 0;
  for (float k : body->bond_state().stiffness) zeroed += k == 0.0f;
  EXPECT_EQ(zeroed, 2 * body->broken_bond_count());
  const BondStore& now = body->bonds();
  EXPECT_EQ(now.row, built.row);
  EXPECT_EQ(now.neighbor, built.neighbor);
  EXPECT_EQ(now.coefficient, built.coefficient);
  // restored to the start: every bond intact again, at the coefficient the store holds
  body->restore_state(start);
  EXPECT_EQ(body->bond_state().stiffness, built.coefficient);
  EXPECT_EQ(body->broken_bond_count(), 0);
  EXPECT_EQ(body->bonds().coefficient, built.coefficient);
}

}  // namespace
}  // namespace periflex
