// A [[flex_body]] read (src/scene/flex_body_section.cpp): every key of the every-key scene, its
// material, notches and loads on regions.
#include <gtest/gtest.h>

#include "every_key_scene.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

using test::expect_vec;
using test::RoundTrip;

TEST_F(RoundTrip, FlexibleBody) {
  ASSERT_EQ(scene.flex_bodies.size(), 2u);
  const FlexBodyDef& plate = scene.flex_bodies[0];
  EXPECT_EQ(plate.name, "plate");
  EXPECT_EQ(plate.shape.kind, ShapeDef::Kind::kBox);
  EXPECT_DOUBLE_EQ(plate.shape.width, 0.1);
  EXPECT_DOUBLE_EQ(plate.shape.height, 0.04);
  ASSERT_EQ(plate.holes.size(), 1u);
  EXPECT_EQ(plate.holes[0].kind, ShapeDef::Kind::kCircle);
  expect_vec(plate.holes[0].center, 0.02, 0.0);
  EXPECT_DOUBLE_EQ(plate.holes[0].radius, 0.005);
  EXPECT_DOUBLE_EQ(plate.grid_spacing, 0.001);
  EXPECT_DOUBLE_EQ(plate.thickness, 0.002);
  EXPECT_DOUBLE_EQ(plate.horizon_ratio, 3.015);
  EXPECT_EQ(plate.influence, FlexBodyDef::Influence::kConical);
  EXPECT_FALSE(plate.partial_volume_correction);
  EXPECT_FALSE(plate.surface_correction);
  EXPECT_FALSE(plate.fracture);
  EXPECT_DOUBLE_EQ(plate.bond_damping, 1.5);
  EXPECT_DOUBLE_EQ(plate.global_damping, 2.5);
  expect_vec(plate.velocity, 0.1, 0.2);
  ASSERT_EQ(plate.notches.size(), 1u);
  expect_vec(plate.notches[0].p1, -0.05, 0.0);
  expect_vec(plate.notches[0].p2, 0.0, 0.0);
  ASSERT_EQ(plate.no_fail_regions.size(), 1u);
  expect_vec(plate.no_fail_regions[0].center, 0.0, 0.019);
  EXPECT_DOUBLE_EQ(plate.no_fail_regions[0].height, 0.003);

  const PdMaterialDef& m = plate.material;
  EXPECT_DOUBLE_EQ(m.youngs_modulus, 72e9);
  EXPECT_DOUBLE_EQ(m.density, 2440.0);
  EXPECT_DOUBLE_EQ(m.critical_stretch, 1e-3);
  EXPECT_DOUBLE_EQ(m.fracture_energy, 0.0);
  EXPECT_TRUE(m.plane_strain);
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 0.25);

  // [flex_body.material] after the second [[flex_body]] belongs to that one
  const FlexBodyDef& tab = scene.flex_bodies[1];
  EXPECT_EQ(tab.shape.kind, ShapeDef::Kind::kPolygon);
  EXPECT_DOUBLE_EQ(tab.material.youngs_modulus, 1e9);
  EXPECT_DOUBLE_EQ(tab.material.fracture_energy, 3.8);
  EXPECT_FALSE(tab.material.plane_strain);
  EXPECT_LT(tab.material.poisson_ratio, 0.0);  // not stated
  EXPECT_DOUBLE_EQ(tab.thickness, 1.0);        // defaults
  EXPECT_DOUBLE_EQ(tab.horizon_ratio, 3.0);
  EXPECT_TRUE(tab.fracture);
  EXPECT_TRUE(tab.loads.empty());
}

TEST_F(RoundTrip, FlexibleBodyLoads) {
  const auto& loads = scene.flex_bodies[0].loads;
  ASSERT_EQ(loads.size(), 4u);
  EXPECT_EQ(loads[0].name, "top");
  EXPECT_EQ(loads[0].kind, RegionLoadDef::Kind::kTraction);
  EXPECT_EQ(loads[0].region.kind, ShapeDef::Kind::kBox);
  EXPECT_FALSE(loads[0].fx.has_value());
  ASSERT_TRUE(loads[0].fy.has_value());
  EXPECT_DOUBLE_EQ((*loads[0].fy)(0.0), 2e6);

  EXPECT_EQ(loads[1].kind, RegionLoadDef::Kind::kPrescribedVelocity);
  EXPECT_EQ(loads[1].region.kind, ShapeDef::Kind::kCircle);
  ASSERT_TRUE(loads[1].fx.has_value());
  EXPECT_DOUBLE_EQ((*loads[1].fx)(5.0), -1.0);
  EXPECT_FALSE(loads[1].fy.has_value());

  EXPECT_EQ(loads[2].kind, RegionLoadDef::Kind::kPrescribedDisplacement);
  EXPECT_EQ(loads[2].region.kind, ShapeDef::Kind::kPolygon);
  ASSERT_TRUE(loads[2].fy.has_value());
  EXPECT_DOUBLE_EQ((*loads[2].fy)(2.0), 0.02);

  EXPECT_EQ(loads[3].kind, RegionLoadDef::Kind::kBodyForce);
  EXPECT_EQ(loads[3].region.kind, ShapeDef::Kind::kBar);
  EXPECT_DOUBLE_EQ(loads[3].region.radius, 0.005);
}

}  // namespace
}  // namespace periflex
