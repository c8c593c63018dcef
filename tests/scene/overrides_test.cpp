// --set overrides change the scene before conversion: each form of path (table key, named
// element, indexed element, inline table, array element) and each kind of value.
#include <gtest/gtest.h>

#include "scene/scene_loader.h"

namespace periflex {
namespace {

const std::string kBase = std::string(PERIFLEX_TEST_DATA) + "/scenes/override_base.toml";

const char* kFlexScene = R"(
[[flex_body]]
name = "plate"
shape = { type = "box", width = 0.1, height = 0.04 }
grid_spacing = 0.001
[flex_body.material]
youngs_modulus = 72e9
density = 2440
fracture_energy = 3.8
[[flex_body.load]]
name = "top"
type = "traction"
region = { type = "box", center = [0, 0.0195], width = 0.1, height = 0.001 }
fy = 2e6
)";

TEST(Overrides, ScalarOfATable) {
  const SceneDef scene = load_scene(kBase, {"solver.dt=1e-4"});
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1e-4);
  EXPECT_DOUBLE_EQ(scene.solver.end_time, 2.0);  // untouched
}

TEST(Overrides, ArrayValueInATableTheFileDoesNotHave) {
  const SceneDef scene = load_scene(kBase, {"scene.gravity=[0,-1.62]"});
  EXPECT_DOUBLE_EQ(scene.gravity.x(), 0.0);
  EXPECT_DOUBLE_EQ(scene.gravity.y(), -1.62);
}

TEST(Overrides, ElementOfAnArrayOfTablesByName) {
  const SceneDef scene = load_scene(kBase, {"body.crank.mass=2"});
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 2.0);
}

TEST(Overrides, ElementOfAnArrayOfTablesByIndex) {
  const SceneDef scene = load_scene(kBase, {"body.0.inertia=0.5"});
  EXPECT_DOUBLE_EQ(scene.bodies[0].inertia, 0.5);
}

TEST(Overrides, KeyInsideAnInlineFunctionTable) {
  const SceneDef scene = load_scene(kBase, {"driver.crank_speed.function.rate=10"});
  EXPECT_EQ(scene.drivers[0].function.kind, TimeFunction::Kind::kRate);
  EXPECT_DOUBLE_EQ(scene.drivers[0].function.rate, 10.0);
  EXPECT_DOUBLE_EQ(scene.drivers[0].function(0.5), 5.0);
}

TEST(Overrides, FunctionReplacedByAConstant) {
  const SceneDef scene = load_scene(kBase, {"driver.crank_speed.function=0.25"});
  EXPECT_EQ(scene.drivers[0].function.kind, TimeFunction::Kind::kConstant);
  EXPECT_DOUBLE_EQ(scene.drivers[0].function(3.0), 0.25);
}

TEST(Overrides, BareWordIsAString) {
  const SceneDef scene = load_scene(kBase, {"solver.integrator=verlet", "solver.correction.method=\"projection\""});
  EXPECT_EQ(scene.solver.integrator, "verlet");
  EXPECT_EQ(scene.solver.correction.method, CorrectionDef::Method::kProjection);
}

TEST(Overrides, BooleanAndInteger) {
  const SceneDef scene = load_scene(kBase, {"solver.auto_substep=true", "solver.threads=3"});
  EXPECT_TRUE(scene.solver.auto_substep);
  EXPECT_EQ(scene.solver.threads, 3);
}

TEST(Overrides, LaterOverrideWins) {
  const SceneDef scene = load_scene(kBase, {"solver.dt=1e-4", "solver.dt=2e-4"});
  EXPECT_DOUBLE_EQ(scene.solver.dt, 2e-4);
}

TEST(Overrides, ElementOfAPlainArray) {
  const SceneDef scene = load_scene(kBase, {"body.crank.position.1=0.25"});
  EXPECT_DOUBLE_EQ(scene.bodies[0].position.x(), 0.5);
  EXPECT_DOUBLE_EQ(scene.bodies[0].position.y(), 0.25);
}

TEST(Overrides, FlexibleBodyMaterialGridAndLoad) {
  const SceneDef scene = parse_scene(kFlexScene, "flex.toml",
                                     {"flex_body.plate.material.youngs_modulus=1e9",
                                      "flex_body.plate.grid_spacing=5e-4", "flex_body.plate.load.top.fy=5"});
  const FlexBodyDef& plate = scene.flex_bodies[0];
  EXPECT_DOUBLE_EQ(plate.material.youngs_modulus, 1e9);
  EXPECT_DOUBLE_EQ(plate.grid_spacing, 5e-4);
  ASSERT_TRUE(plate.loads[0].fy.has_value());
  EXPECT_DOUBLE_EQ((*plate.loads[0].fy)(0.0), 5.0);
}

// An override's array is checked element by element and blamed on the override.
TEST(Overrides, BadElementOfAnOverriddenArrayNamesTheOverride) {
  try {
    load_scene(kBase, {"scene.gravity=[0, nan]"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "--set");
    EXPECT_EQ(e.where().key, "scene.gravity");
    EXPECT_NE(std::string(e.what()).find("override 'scene.gravity=[0, nan]'"), std::string::npos) << e.what();
  }
}

// A refused grid refinement must be refused before allocation, naming the override.
TEST(Overrides, GridRefinementBeyondTheParticleLimitIsRefused) {
  try {
    parse_scene(kFlexScene, "flex.toml", {"flex_body.plate.grid_spacing=1e-6"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "--set");
    // 0.1 m x 0.04 m / (1e-6 m)^2 = 4e9 particles, written as a whole number
    EXPECT_NE(std::string(e.what()).find("about 4000000000 particles"), std::string::npos) << e.what();
  }
}

// Values the file still holds keep their file positions after unrelated overrides.
TEST(Overrides, FileErrorsKeepTheirLines) {
  try {
    parse_scene("[[body]]\nname = \"a\"\nmass = -1\n", "f.toml", {"solver.dt=1e-4"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "f.toml");
    EXPECT_EQ(e.where().line, 3);
  }
}

}  // namespace
}  // namespace periflex
