// The constraint rows of Dynamics (solve/dynamics_rows.cpp): dependent rows left out and named,
// the rank saved and restored, the worst block named.
#include <gtest/gtest.h>

#include <algorithm>

#include "model/system_model.h"
#include "solve/dynamics.h"
#include "test_scenes.h"

namespace periflex {
namespace {

// a double pendulum whose shoulder is pinned twice at the same point: two rows too many
SceneDef pinned_twice() {
  SceneDef s = test::double_pendulum("rk4", 1e-3, CorrectionDef::Method::kProjection);
  s.joints.push_back(test::revolute("shoulder_again", "ground", "upper", Vec2::Zero(), Vec2(-0.5, 0.0)));
  return s;
}

TEST(DynamicsRows, ARepeatedPinLeavesTwoRowsOutAndNamesTheirBlock) {
  auto model = build_system_model(pinned_twice());
  ASSERT_EQ(model->constraint_rows, 6);
  Dynamics dynamics(*model);
  dynamics.analyse(0.0);
  EXPECT_EQ(dynamics.independent_rows(), 4);
  // one of the two pins is redundant; the rows left out are both of one of them
  const std::vector<int>& dropped = dynamics.dropped_rows();
  ASSERT_EQ(dropped.size(), 2u);
  const std::vector<std::string> blocks = dynamics.blocks_of(dropped);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_TRUE(blocks[0] == "shoulder" || blocks[0] == "shoulder_again") << blocks[0];
  EXPECT_EQ(dynamics.dropped_blocks(), blocks);
}

TEST(DynamicsRows, AnIndependentSystemKeepsEveryRow) {
  auto model = build_system_model(test::double_pendulum("rk4", 1e-3, CorrectionDef::Method::kProjection));
  Dynamics dynamics(*model);
  dynamics.analyse(0.0);
  EXPECT_TRUE(dynamics.dropped_rows().empty());
  EXPECT_EQ(dynamics.independent_rows(), model->constraint_rows);
  EXPECT_EQ(dynamics.active_rows(), model->constraint_rows);
}

TEST(DynamicsRows, RankSavedAndRestoredLeavesOutTheSameRows) {
  auto model = build_system_model(pinned_twice());
  Dynamics first(*model);
  first.analyse(0.0);
  RankState saved;
  first.save_rank(saved);

  // a state saved after the rank changed seven times
  saved.rank_changes = 7;
  Dynamics second(*model);
  second.analyse(0.0);
  ASSERT_EQ(second.rank_changes(), 0);
  second.restore_rank(saved);
  EXPECT_EQ(second.dropped_rows(), first.dropped_rows());
  EXPECT_EQ(second.rank_changes(), 7);
}

TEST(DynamicsRows, WorstConstraintNamesTheBlockMovedApart) {
  auto model = build_system_model(test::double_pendulum("rk4", 1e-3, CorrectionDef::Method::kProjection));
  Dynamics dynamics(*model);
  dynamics.analyse(0.0);
  // the lower bar pulled 1 mm off the upper one: the elbow opens, the shoulder holds
  Eigen::VectorXd q = model->q0;
  q[3] += 1e-3;
  EXPECT_EQ(dynamics.worst_constraint(0.0, q), "elbow");
  // and the upper bar pulled off the ground: the shoulder opens by more than the elbow
  q = model->q0;
  q[1] += 2e-3;
  q[4] += 1e-3;
  EXPECT_EQ(dynamics.worst_constraint(0.0, q), "shoulder");
}

}  // namespace
}  // namespace periflex
