// The model's typed list of rigid-flexible joints (SystemModel::attachments) against the
// constraint blocks that own them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "core/error.h"
#include "io/image.h"
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

// A bar drawn black with blue ends, each end held by a virtual body through pixels = "blue"
// within a box around it (or, for the second grip, every blue pixel right of the middle): each
// grip holds exactly its end's blue particles. A body not read from a picture is refused.
TEST(SystemModel, AttachmentsHoldTheBluePixelsOfAPicture) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "periflex_blue_grips";
  fs::create_directories(dir);
  RgbaImage image;
  image.resize(40, 10);  // 40 x 10 mm at 1 mm: columns 0-4 and 35-39 blue
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 40; ++x) {
      const bool blue = x < 5 || x >= 35;
      const uint8_t pixel[4] = {static_cast<uint8_t>(blue ? 20 : 0), static_cast<uint8_t>(blue ? 20 : 0),
                                static_cast<uint8_t>(blue ? 230 : 0), 255};
      std::copy(pixel, pixel + 4, image.at(x, y));
    }
  write_png((dir / "bar.png").string(), image);
  const std::string scene_text = R"([scene]
name = "blue_grips"
gravity = [0.0, 0.0]

[solver]
integrator = "verlet"
dt = 1e-7
end_time = 1e-6

[[body]]
name = "left"
virtual = true
mass = 0.0
inertia = 0.0
position = [-0.0175, 0.0]

[[body]]
name = "right"
virtual = true
mass = 0.0
inertia = 0.0
position = [0.0175, 0.0]

[[flex_body]]
name = "bar"
shape = { type = "image", file = "bar.png", width = 0.04 }
grid_spacing = 1e-3
thickness = 1e-3

[flex_body.material]
youngs_modulus = 3e9
density = 1200.0
fracture_energy = 300.0

[[attachment]]
name = "left_grip"
body = "left"
flex_body = "bar"
pixels = "blue"
region = { type = "box", center = [-0.02, 0.0], width = 0.02, height = 0.02 }

[[attachment]]
name = "right_grip"
body = "right"
flex_body = "bar"
pixels = "blue"
region = { type = "box", center = [0.02, 0.0], width = 0.02, height = 0.02 }
)";
  std::ofstream(dir / "blue.toml") << scene_text;
  const auto model = build_system_model(load_scene((dir / "blue.toml").string()));
  ASSERT_EQ(model->attachments.size(), 2u);
  for (const Attachment& attachment : model->attachments) {
    EXPECT_EQ(attachment.joint->particle_count(), 5 * 10);  // five blue columns of ten
    // every held particle lies in its end's blue columns
    for (int k = 0; k < attachment.joint->particle_count(); ++k) {
      const double x = model->q0[attachment.joint->particle_coordinates()[k]];
      EXPECT_GT(std::abs(x), 0.0149) << x;
    }
  }

  // pixels = "blue" on a body drawn by shape rather than read from a picture
  std::string boxed = scene_text;
  boxed.replace(boxed.find(R"({ type = "image", file = "bar.png", width = 0.04 })"),
                std::string(R"({ type = "image", file = "bar.png", width = 0.04 })").size(),
                R"({ type = "box", width = 0.04, height = 0.01 })");
  std::ofstream(dir / "boxed.toml") << boxed;
  try {
    load_scene((dir / "boxed.toml").string());
    ADD_FAILURE() << "pixels = \"blue\" accepted on a body not read from a picture";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pixels"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("picture"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace periflex
