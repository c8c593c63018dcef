// A scene that states every key of the schema with a non-default value, and a check of every
// field of the SceneDef it becomes. Expected values are the ones typed in the text (or, for
// normalised axes and defaults, worked out by hand), never output of the loader itself.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.h"

namespace periflex {
namespace {

const char* kEveryKey = R"toml(
[scene]
name = "everything"
description = "every key"
gravity = [0.5, -1.62]

[solver]
integrator = "dopri54"
dt = 2e-4
end_time = 3
rtol = 1e-7
atol = 1e-10
output_interval = 0.02
auto_substep = true
dt_safety = 0.5
threads = 2
hht_alpha = -0.2

[solver.correction]
method = "projection"
alpha = 7.0
beta = 8.0
tolerance = 1e-11
max_iterations = 20

[[body]]
name = "crank"
mass = 2.5
inertia = 0.125
position = [0.1, 0.2]
angle = 0.3
velocity = [1.0, -2.0]
angular_velocity = 4.0
shape = { type = "bar", p1 = [-0.5, 0], p2 = [0.5, 0], width = 0.04 }

[[body]]
name = "hub"
virtual = true
mass = 0
inertia = 0
shapes = [ { type = "box", center = [1, 2], width = 0.3, height = 0.2, angle = 0.1 },
           { type = "circle", center = [0, 1], radius = 0.25 },
           { type = "polygon", vertices = [[0, 0], [1, 0], [0, 1]] } ]

[[joint]]
name = "pin"
type = "revolute"
body_i = "ground"
body_j = "crank"
point_i = [0.25, 0.5]
point_j = [-0.5, 0.0]

[[joint]]
name = "slide"
type = "translational"
body_i = "crank"
body_j = "hub"
point_i = [0.1, 0]
point_j = [0.2, 0]
axis_i = [3, 4]
axis_j = [0, 2]

[[joint]]
name = "weld"
type = "rigid"
body_i = "crank"
body_j = "hub"
relative_angle = 0.7

[[joint]]
name = "link"
type = "revolute_revolute"
body_i = "ground"
body_j = "hub"
length = 1.5

[[joint]]
name = "rail"
type = "revolute_translational"
body_i = "hub"
body_j = "crank"
axis_i = [0, -1]
offset = 0.05

[[driver]]
name = "spin"
type = "absolute_angle"
body_i = "crank"
function = { type = "rate", value = 0.3, rate = 6.5 }

[[driver]]
name = "twist"
type = "relative_angle"
body_i = "crank"
body_j = "hub"
function = { type = "harmonic", offset = 0.1, amplitude = 0.2, omega = 3.0, phase = 0.4 }

[[driver]]
name = "lift"
type = "absolute_position"
body_i = "hub"
point_i = [0.1, 0.1]
axis = [0, 5]
function = { type = "polynomial", coefficients = [1.0, 2.0, 3.0] }

[[driver]]
name = "stroke"
type = "relative_position"
body_i = "ground"
body_j = "hub"
point_i = [1, 1]
point_j = [2, 2]
axis = [1, 0]
function = { type = "table", times = [0, 1, 2], values = [0, 1, 0] }

[[force]]
name = "spring"
type = "spring_damper"
body_i = "ground"
body_j = "crank"
point_i = [0, 1]
point_j = [0.5, 0]
stiffness = 100.0
damping = 0.5
free_length = 0.4
actuator = { type = "constant", value = 3.0 }

[[force]]
name = "coil"
type = "rotational_spring"
body_i = "crank"
body_j = "ground"
stiffness = 20.0
damping = 0.25
free_angle = 0.15

[[force]]
name = "push"
type = "force"
body_i = "crank"
point_i = [0.3, 0]
direction = [0, -2]
magnitude = 10

[[force]]
name = "motor"
type = "torque"
body_i = "crank"
magnitude = { type = "rate", rate = 2.0 }

[[probe]]
name = "tip"
body = "crank"
point = [0.5, 0.0]

[[probe]]
name = "corner"
body = "plate"
point = [0.05, 0.02]

[[flex_body]]
name = "plate"
shape = { type = "box", center = [0, 0], width = 0.1, height = 0.04 }
holes = [ { type = "circle", center = [0.02, 0], radius = 0.005 } ]
grid_spacing = 0.001
thickness = 0.002
horizon_ratio = 3.015
influence = "conical"
partial_volume_correction = false
surface_correction = false
fracture = false
bond_damping = 1.5
global_damping = 2.5
velocity = [0.1, 0.2]
notches = [ { p1 = [-0.05, 0.0], p2 = [0.0, 0.0] } ]
no_fail = [ { type = "box", center = [0, 0.019], width = 0.1, height = 0.003 } ]

[flex_body.material]
youngs_modulus = 72e9
density = 2440.0
critical_stretch = 1e-3
plane = "strain"
poisson_ratio = 0.25

[[flex_body.load]]
name = "top"
type = "traction"
region = { type = "box", center = [0, 0.0195], width = 0.1, height = 0.001 }
fy = 2e6

[[flex_body.load]]
name = "left"
type = "prescribed_velocity"
region = { type = "circle", center = [-0.05, 0], radius = 0.002 }
fx = -1.0

[[flex_body.load]]
name = "right"
type = "prescribed_displacement"
region = { type = "polygon", vertices = [[0.04, -0.02], [0.05, -0.02], [0.05, 0.02]] }
fx = 0
fy = { type = "rate", rate = 0.01 }

[[flex_body.load]]
name = "weight"
type = "body_force"
region = { type = "bar", p1 = [-0.05, 0], p2 = [0.05, 0], width = 0.01 }
fy = -9.81

[[flex_body]]
name = "tab"
shape = { type = "polygon", vertices = [[0, 0], [0.01, 0], [0.01, 0.01], [0, 0.01]] }
grid_spacing = 0.001

[flex_body.material]
youngs_modulus = 1e9
density = 1000
fracture_energy = 3.8

[[attachment]]
name = "grip"
body = "hub"
flex_body = "plate"
region = { type = "box", center = [-0.048, 0], width = 0.004, height = 0.04 }

[[contact]]
name = "strike"
type = "rigid_particles"
body = "crank"
flex_body = "plate"
stiffness = 2e6
restitution = 0.5
friction = 0.3
friction_velocity = 0.01
margin = 0.002

[[contact]]
name = "faces"
type = "particles"
flex_bodies = ["plate", "tab"]
stiffness = 3e5
restitution = 0.9
distance_ratio = 0.8
skin_ratio = 0.3
)toml";

void expect_vec(const Vec2& v, double x, double y) {
  EXPECT_DOUBLE_EQ(v.x(), x);
  EXPECT_DOUBLE_EQ(v.y(), y);
}

class RoundTrip : public ::testing::Test {
 protected:
  SceneDef scene = parse_scene(kEveryKey, "dir/every.toml");
};

TEST_F(RoundTrip, SceneAndSolver) {
  EXPECT_EQ(scene.name, "everything");
  EXPECT_EQ(scene.description, "every key");
  EXPECT_EQ(scene.path, "dir/every.toml");
  expect_vec(scene.gravity, 0.5, -1.62);
  const SolverDef& s = scene.solver;
  EXPECT_EQ(s.integrator, "dopri54");
  EXPECT_DOUBLE_EQ(s.dt, 2e-4);
  EXPECT_DOUBLE_EQ(s.end_time, 3.0);
  EXPECT_DOUBLE_EQ(s.rtol, 1e-7);
  EXPECT_DOUBLE_EQ(s.atol, 1e-10);
  EXPECT_DOUBLE_EQ(s.output_interval, 0.02);
  EXPECT_TRUE(s.auto_substep);
  EXPECT_DOUBLE_EQ(s.dt_safety, 0.5);
  EXPECT_EQ(s.threads, 2);
  EXPECT_DOUBLE_EQ(s.hht_alpha, -0.2);
  EXPECT_EQ(s.correction.method, CorrectionDef::Method::kProjection);
  EXPECT_DOUBLE_EQ(s.correction.alpha, 7.0);
  EXPECT_DOUBLE_EQ(s.correction.beta, 8.0);
  EXPECT_DOUBLE_EQ(s.correction.tolerance, 1e-11);
  EXPECT_EQ(s.correction.max_iterations, 20);
}

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

// Absent sections and keys take the documented defaults.
TEST(SceneDefaults, MinimalSceneTakesDefaults) {
  const SceneDef scene = parse_scene("[[body]]\nname = \"b\"\n", "some/where/minimal.toml");
  EXPECT_EQ(scene.name, "minimal");  // the file stem
  expect_vec(scene.gravity, 0.0, -9.81);
  EXPECT_EQ(scene.solver.integrator, "rk4");
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1e-3);
  EXPECT_EQ(scene.solver.correction.method, CorrectionDef::Method::kBaumgarte);
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 1.0);
  EXPECT_DOUBLE_EQ(scene.bodies[0].inertia, 1.0);
  EXPECT_TRUE(scene.bodies[0].shapes.empty());
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

TEST(SceneFunctions, IntegersAreAcceptedWhereFloatsAreExpected) {
  const SceneDef scene = parse_scene(R"(
[solver]
dt = 1
end_time = 2
[[body]]
name = "a"
mass = 3
position = [1, 2]
)", "x.toml");
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1.0);
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 3.0);
  expect_vec(scene.bodies[0].position, 1.0, 2.0);
}

}  // namespace
}  // namespace periflex
