// Only the parts a model needs are switched on: a rigid mechanism runs no peridynamics, a free
// flexible body runs no constraint solver, and a coupled scene runs both.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "coupled_run.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

bool mentions(const std::vector<std::string>& modules, const std::string& word) {
  return std::any_of(modules.begin(), modules.end(),
                     [&](const std::string& m) { return m.find(word) != std::string::npos; });
}

TEST(Modules, RigidPendulumListsNoPeridynamics) {
  SceneDef scene;
  scene.name = "rigid_pendulum";
  BodyDef bar;
  bar.name = "bar";
  bar.mass = 1.0;
  bar.inertia = 1.0 / 12.0;
  bar.position = Vec2(0.5, 0.0);
  scene.bodies.push_back(bar);
  JointDef pin;
  pin.name = "pin";
  pin.body_i = "ground";
  pin.body_j = "bar";
  pin.point_i = Vec2(0.0, 0.0);
  pin.point_j = Vec2(-0.5, 0.0);
  scene.joints.push_back(pin);

  Simulation sim(scene);
  const ModelInfo& info = sim.info();
  EXPECT_EQ(info.flex_bodies, 0);
  EXPECT_EQ(info.particles, 0);
  EXPECT_TRUE(mentions(info.active_modules, "constraint")) << "a pinned bar needs the constraint solver";
  EXPECT_FALSE(mentions(info.active_modules, "pd")) << "no flexible body, no peridynamics";
}

TEST(Modules, FreeFlexibleBodyListsNoConstraintSolver) {
  SceneDef scene;
  scene.name = "free_plate";
  FlexBodyDef plate;
  plate.name = "plate";
  plate.shape.kind = ShapeDef::Kind::kBox;
  plate.shape.width = 0.02;
  plate.shape.height = 0.01;
  plate.grid_spacing = 1e-3;
  plate.thickness = 1e-3;
  plate.material.youngs_modulus = 1e9;
  plate.material.density = 1000.0;
  plate.material.critical_stretch = 1e-2;
  scene.flex_bodies.push_back(plate);

  Simulation sim(scene);
  const ModelInfo& info = sim.info();
  EXPECT_EQ(info.flex_bodies, 1);
  EXPECT_EQ(info.particles, 200);
  EXPECT_EQ(info.constraint_equations, 0);
  EXPECT_TRUE(mentions(info.active_modules, "pd"));
  EXPECT_FALSE(mentions(info.active_modules, "constraint")) << "nothing to constrain";
}

TEST(Modules, CoupledSceneListsBothAndCountsTwoEquationsPerAttachedParticle) {
  const SceneDef scene = load_scene(test::scene_path("flexible_pendulum"));
  Simulation sim(scene);
  const ModelInfo& info = sim.info();
  EXPECT_TRUE(mentions(info.active_modules, "pd"));
  EXPECT_TRUE(mentions(info.active_modules, "constraint"));
  EXPECT_EQ(info.virtual_bodies, 1);
  // the hub clamp holds 4 columns x 4 rows of the 10 mm grid; the pivot adds 2 equations
  EXPECT_EQ(info.constraint_equations, 2 * 16 + 2);
  // hub (3) + 208 particles (2 each) - 34 equations
  EXPECT_EQ(info.coordinates, 3 + 2 * 208);
  EXPECT_EQ(info.degrees_of_freedom, 3 + 2 * 208 - 34);
}

}  // namespace
}  // namespace periflex
