// [[probe]], [[attachment]] and [[contact]] read (src/scene/mechanism_sections.cpp,
// src/scene/coupling_sections.cpp): every key of the every-key scene.
#include <gtest/gtest.h>

#include "every_key_scene.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

using test::expect_vec;
using test::RoundTrip;

TEST_F(RoundTrip, ProbesAndAttachments) {
  ASSERT_EQ(scene.probes.size(), 2u);
  EXPECT_EQ(scene.probes[0].name, "tip");
  EXPECT_EQ(scene.probes[0].body, "crank");
  expect_vec(scene.probes[0].point, 0.5, 0.0);
  EXPECT_EQ(scene.probes[1].body, "plate");  // probes may name flexible bodies
  ASSERT_EQ(scene.attachments.size(), 1u);
  const AttachmentDef& grip = scene.attachments[0];
  EXPECT_EQ(grip.name, "grip");
  EXPECT_EQ(grip.body, "hub");
  EXPECT_EQ(grip.flex_body, "plate");
  EXPECT_EQ(grip.region.kind, ShapeDef::Kind::kBox);
  expect_vec(grip.region.center, -0.048, 0.0);
  EXPECT_DOUBLE_EQ(grip.region.width, 0.004);
  EXPECT_DOUBLE_EQ(grip.region.height, 0.04);
}

TEST_F(RoundTrip, Contacts) {
  ASSERT_EQ(scene.contacts.size(), 2u);
  const ContactDef& strike = scene.contacts[0];
  EXPECT_EQ(strike.name, "strike");
  EXPECT_EQ(strike.kind, ContactDef::Kind::kRigidParticles);
  EXPECT_EQ(strike.body, "crank");
  ASSERT_EQ(strike.flex_bodies.size(), 1u);
  EXPECT_EQ(strike.flex_bodies[0], "plate");
  EXPECT_DOUBLE_EQ(strike.stiffness, 2e6);
  EXPECT_DOUBLE_EQ(strike.restitution, 0.5);
  EXPECT_DOUBLE_EQ(strike.friction, 0.3);
  EXPECT_DOUBLE_EQ(strike.friction_velocity, 0.01);
  EXPECT_DOUBLE_EQ(strike.margin, 0.002);
  const ContactDef& faces = scene.contacts[1];
  EXPECT_EQ(faces.kind, ContactDef::Kind::kParticles);
  ASSERT_EQ(faces.flex_bodies.size(), 2u);
  EXPECT_EQ(faces.flex_bodies[1], "tab");
  EXPECT_DOUBLE_EQ(faces.stiffness, 3e5);
  EXPECT_DOUBLE_EQ(faces.restitution, 0.9);
  EXPECT_DOUBLE_EQ(faces.distance_ratio, 0.8);
  EXPECT_DOUBLE_EQ(faces.skin_ratio, 0.3);
}

}  // namespace
}  // namespace periflex
