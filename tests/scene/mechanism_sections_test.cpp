// [[body]], [[joint]], [[driver]] and [[force]] read (src/scene/mechanism_sections.cpp): every key
// of the every-key scene, joint geometry taken from the initial configuration when omitted, a
// clockwise polygon stored counter-clockwise.
#include <gtest/gtest.h>

#include <cmath>

#include "every_key_scene.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

using test::expect_vec;
using test::RoundTrip;

TEST_F(RoundTrip, Bodies) {
  ASSERT_EQ(scene.bodies.size(), 2u);
  const BodyDef& crank = scene.bodies[0];
  EXPECT_EQ(crank.name, "crank");
  EXPECT_DOUBLE_EQ(crank.mass, 2.5);
  EXPECT_DOUBLE_EQ(crank.inertia, 0.125);
  expect_vec(crank.position, 0.1, 0.2);
  EXPECT_DOUBLE_EQ(crank.angle, 0.3);
  expect_vec(crank.velocity, 1.0, -2.0);
  EXPECT_DOUBLE_EQ(crank.angular_velocity, 4.0);
  EXPECT_FALSE(crank.is_virtual);
  EXPECT_FALSE(crank.ground);
  EXPECT_EQ(crank.where.file, "dir/every.toml");
  EXPECT_EQ(crank.where.line, 26);  // the [[body]] header (the text opens with a newline)
  ASSERT_EQ(crank.shapes.size(), 1u);
  EXPECT_EQ(crank.shapes[0].kind, ShapeDef::Kind::kBar);
  expect_vec(crank.shapes[0].p1, -0.5, 0.0);
  expect_vec(crank.shapes[0].p2, 0.5, 0.0);
  EXPECT_DOUBLE_EQ(crank.shapes[0].radius, 0.02);  // width / 2

  const BodyDef& hub = scene.bodies[1];
  EXPECT_TRUE(hub.is_virtual);
  EXPECT_DOUBLE_EQ(hub.mass, 0.0);
  EXPECT_DOUBLE_EQ(hub.inertia, 0.0);
  expect_vec(hub.position, 0.0, 0.0);
  ASSERT_EQ(hub.shapes.size(), 3u);
  EXPECT_EQ(hub.shapes[0].kind, ShapeDef::Kind::kBox);
  expect_vec(hub.shapes[0].center, 1.0, 2.0);
  EXPECT_DOUBLE_EQ(hub.shapes[0].width, 0.3);
  EXPECT_DOUBLE_EQ(hub.shapes[0].height, 0.2);
  EXPECT_DOUBLE_EQ(hub.shapes[0].angle, 0.1);
  EXPECT_EQ(hub.shapes[1].kind, ShapeDef::Kind::kCircle);
  expect_vec(hub.shapes[1].center, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(hub.shapes[1].radius, 0.25);
  EXPECT_EQ(hub.shapes[2].kind, ShapeDef::Kind::kPolygon);
  ASSERT_EQ(hub.shapes[2].vertices.size(), 3u);
  expect_vec(hub.shapes[2].vertices[1], 1.0, 0.0);
}

TEST_F(RoundTrip, Joints) {
  ASSERT_EQ(scene.joints.size(), 5u);
  const JointDef& pin = scene.joints[0];
  EXPECT_EQ(pin.kind, JointDef::Kind::kRevolute);
  EXPECT_EQ(pin.name, "pin");
  EXPECT_EQ(pin.body_i, "ground");
  EXPECT_EQ(pin.body_j, "crank");
  expect_vec(pin.point_i, 0.25, 0.5);
  expect_vec(pin.point_j, -0.5, 0.0);

  const JointDef& slide = scene.joints[1];
  EXPECT_EQ(slide.kind, JointDef::Kind::kTranslational);
  expect_vec(slide.point_i, 0.1, 0.0);
  expect_vec(slide.point_j, 0.2, 0.0);
  expect_vec(slide.axis_i, 0.6, 0.8);  // [3, 4] normalised
  expect_vec(slide.axis_j, 0.0, 1.0);

  const JointDef& weld = scene.joints[2];
  EXPECT_EQ(weld.kind, JointDef::Kind::kRigid);
  EXPECT_DOUBLE_EQ(weld.relative_angle, 0.7);
  EXPECT_FALSE(weld.relative_angle_from_initial);

  const JointDef& link = scene.joints[3];
  EXPECT_EQ(link.kind, JointDef::Kind::kRevoluteRevolute);
  EXPECT_DOUBLE_EQ(link.length, 1.5);
  EXPECT_FALSE(link.length_from_initial);

  const JointDef& rail = scene.joints[4];
  EXPECT_EQ(rail.kind, JointDef::Kind::kRevoluteTranslational);
  expect_vec(rail.axis_i, 0.0, -1.0);
  EXPECT_DOUBLE_EQ(rail.offset, 0.05);
}

TEST_F(RoundTrip, DriversAndTheirFunctions) {
  ASSERT_EQ(scene.drivers.size(), 4u);
  const DriverDef& spin = scene.drivers[0];
  EXPECT_EQ(spin.kind, DriverDef::Kind::kAbsoluteAngle);
  EXPECT_EQ(spin.body_i, "crank");
  EXPECT_EQ(spin.function.kind, TimeFunction::Kind::kRate);
  EXPECT_DOUBLE_EQ(spin.function.value, 0.3);
  EXPECT_DOUBLE_EQ(spin.function.rate, 6.5);

  const DriverDef& twist = scene.drivers[1];
  EXPECT_EQ(twist.kind, DriverDef::Kind::kRelativeAngle);
  EXPECT_EQ(twist.body_j, "hub");
  EXPECT_EQ(twist.function.kind, TimeFunction::Kind::kHarmonic);
  EXPECT_DOUBLE_EQ(twist.function.offset, 0.1);
  EXPECT_DOUBLE_EQ(twist.function.amplitude, 0.2);
  EXPECT_DOUBLE_EQ(twist.function.omega, 3.0);
  EXPECT_DOUBLE_EQ(twist.function.phase, 0.4);

  const DriverDef& lift = scene.drivers[2];
  EXPECT_EQ(lift.kind, DriverDef::Kind::kAbsolutePosition);
  expect_vec(lift.point_i, 0.1, 0.1);
  expect_vec(lift.axis, 0.0, 1.0);  // [0, 5] normalised
  EXPECT_EQ(lift.function.kind, TimeFunction::Kind::kPolynomial);
  EXPECT_EQ(lift.function.coefficients, (std::vector<double>{1.0, 2.0, 3.0}));

  const DriverDef& stroke = scene.drivers[3];
  EXPECT_EQ(stroke.kind, DriverDef::Kind::kRelativePosition);
  EXPECT_EQ(stroke.body_i, "ground");
  expect_vec(stroke.point_i, 1.0, 1.0);
  expect_vec(stroke.point_j, 2.0, 2.0);
  EXPECT_EQ(stroke.function.kind, TimeFunction::Kind::kTable);
  EXPECT_EQ(stroke.function.times, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(stroke.function.values, (std::vector<double>{0.0, 1.0, 0.0}));
  // piecewise linear: halfway up the first segment
  EXPECT_DOUBLE_EQ(stroke.function(0.5), 0.5);
}

TEST_F(RoundTrip, Forces) {
  ASSERT_EQ(scene.forces.size(), 4u);
  const ForceDef& spring = scene.forces[0];
  EXPECT_EQ(spring.kind, ForceDef::Kind::kSpringDamper);
  expect_vec(spring.point_i, 0.0, 1.0);
  expect_vec(spring.point_j, 0.5, 0.0);
  EXPECT_DOUBLE_EQ(spring.stiffness, 100.0);
  EXPECT_DOUBLE_EQ(spring.damping, 0.5);
  EXPECT_DOUBLE_EQ(spring.free_length, 0.4);
  EXPECT_EQ(spring.actuator.kind, TimeFunction::Kind::kConstant);
  EXPECT_DOUBLE_EQ(spring.actuator.value, 3.0);

  const ForceDef& coil = scene.forces[1];
  EXPECT_EQ(coil.kind, ForceDef::Kind::kRotationalSpring);
  EXPECT_EQ(coil.body_j, "ground");
  EXPECT_DOUBLE_EQ(coil.stiffness, 20.0);
  EXPECT_DOUBLE_EQ(coil.damping, 0.25);
  EXPECT_DOUBLE_EQ(coil.free_angle, 0.15);
  EXPECT_FALSE(coil.free_angle_from_initial);

  const ForceDef& push = scene.forces[2];
  EXPECT_EQ(push.kind, ForceDef::Kind::kForce);
  expect_vec(push.point_i, 0.3, 0.0);
  expect_vec(push.direction, 0.0, -1.0);
  EXPECT_EQ(push.magnitude.kind, TimeFunction::Kind::kConstant);
  EXPECT_DOUBLE_EQ(push.magnitude.value, 10.0);

  const ForceDef& motor = scene.forces[3];
  EXPECT_EQ(motor.kind, ForceDef::Kind::kTorque);
  EXPECT_EQ(motor.magnitude.kind, TimeFunction::Kind::kRate);
  EXPECT_DOUBLE_EQ(motor.magnitude.value, 0.0);  // default of a rate function
  EXPECT_DOUBLE_EQ(motor.magnitude.rate, 2.0);
}

TEST(SceneDefaults, OmittedJointGeometryIsTakenFromTheInitialConfiguration) {
  const SceneDef scene = parse_scene(R"(
[[body]]
name = "a"
[[joint]]
name = "l"
type = "revolute_revolute"
body_i = "ground"
body_j = "a"
[[joint]]
name = "w"
type = "rigid"
body_i = "ground"
body_j = "a"
[[force]]
name = "s"
type = "spring_damper"
body_i = "ground"
body_j = "a"
stiffness = 1
)", "x.toml");
  EXPECT_TRUE(scene.joints[0].length_from_initial);
  EXPECT_LT(scene.joints[0].length, 0.0);
  EXPECT_TRUE(scene.joints[1].relative_angle_from_initial);
  EXPECT_LT(scene.forces[0].free_length, 0.0);
  EXPECT_DOUBLE_EQ(scene.forces[0].actuator(1.0), 0.0);
}

TEST(SceneShapes, ClockwisePolygonIsReversedToCounterClockwise) {
  const SceneDef scene = parse_scene(R"(
[[body]]
name = "a"
shape = { type = "polygon", vertices = [[0, 0], [0, 1], [1, 0]] }
)", "x.toml");
  const auto& v = scene.bodies[0].shapes[0].vertices;
  ASSERT_EQ(v.size(), 3u);
  // signed area of the stored order must be +1/2
  const double area2 = cross(v[0], v[1]) + cross(v[1], v[2]) + cross(v[2], v[0]);
  EXPECT_DOUBLE_EQ(area2, 1.0);
}

}  // namespace
}  // namespace periflex
