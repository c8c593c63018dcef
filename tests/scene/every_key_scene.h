// A scene that states every key of the schema with a non-default value, shared by the tests of
// the scene reader's sections (solver_sections_test.cpp, mechanism_sections_test.cpp,
// flex_body_section_test.cpp, coupling_sections_test.cpp), each of which checks every field of
// its sections in the SceneDef it becomes. Expected values are the ones typed in the text (or,
// for normalised axes and defaults, worked out by hand), never output of the loader itself.
#pragma once

#include <gtest/gtest.h>

#include "scene/scene_loader.h"

namespace periflex::test {

inline const char* const kEveryKey = R"toml(
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

inline void expect_vec(const Vec2& v, double x, double y) {
  EXPECT_DOUBLE_EQ(v.x(), x);
  EXPECT_DOUBLE_EQ(v.y(), y);
}

// The every-key scene, parsed once per test.
class RoundTrip : public ::testing::Test {
 protected:
  SceneDef scene = parse_scene(kEveryKey, "dir/every.toml");
};

}  // namespace periflex::test
