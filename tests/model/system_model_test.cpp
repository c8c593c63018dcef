// The model's typed list of rigid-flexible joints (SystemModel::attachments) against the
// constraint blocks that own them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "model/system_model.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

std::string shipped(const std::string& stem) { return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + stem + ".toml"; }

// the flexible four-bar holds its coupler by two grips, between revolute joints and drivers
TEST(SystemModel, AttachmentsListEveryRigidFlexibleJointOnceInConstraintOrder) {
  const SceneDef scene = load_scene(shipped("flexible_four_bar"));
  ASSERT_EQ(scene.attachments.size(), 2u);
  const auto model = build_system_model(scene);
  ASSERT_EQ(model->attachments.size(), scene.attachments.size());

  std::set<int> listed;
  int previous = -1;
  for (size_t k = 0; k < model->attachments.size(); ++k) {
    const Attachment& attachment = model->attachments[k];
    ASSERT_GE(attachment.block, 0);
    ASSERT_LT(attachment.block, static_cast<int>(model->constraints.size()));
    const ConstraintBlock& block = model->constraints[attachment.block];
    // the list points at the joint its block owns, with the block's rows
    EXPECT_EQ(attachment.joint, block.constraint.get());
    EXPECT_EQ(block.origin, ConstraintBlock::Origin::kAttachment);
    EXPECT_EQ(attachment.first_row, block.first_row);
    EXPECT_EQ(attachment.joint->rows(), 2 * attachment.joint->particle_count());
    EXPECT_EQ(attachment.joint->name(), scene.attachments[k].name);
    EXPECT_GT(attachment.block, previous);
    previous = attachment.block;
    listed.insert(attachment.block);
  }
  // and no attachment block is left out of it
  for (size_t b = 0; b < model->constraints.size(); ++b) {
    const bool attachment = model->constraints[b].origin == ConstraintBlock::Origin::kAttachment;
    EXPECT_EQ(attachment, listed.count(static_cast<int>(b)) == 1) << "block " << b;
  }
}

// a rigid scene builds an empty list
TEST(SystemModel, RigidSceneHasNoAttachments) {
  const auto model = build_system_model(load_scene(shipped("four_bar")));
  EXPECT_TRUE(model->attachments.empty());
  EXPECT_FALSE(model->constraints.empty());
}

}  // namespace
}  // namespace periflex
