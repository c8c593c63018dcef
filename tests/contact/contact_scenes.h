// Scene texts shared by the contact tests: a rigid striker on a free steel strip (the 1D
// impact of wave theory) and two discs thrown at each other.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace periflex::test {

// A striker box of mass `mass` at 1 m/s against the end of a free 1 m x 50 mm steel strip
// (20 mm thick, 7.85 kg, dx = 10 mm: 100 x 5 particles), no gravity, Verlet. The striker's face
// starts 1 um from the strip's surface. `contact_extra` is appended to the [[contact]] table.
inline std::string strip_scene(double mass, double dt, double end_time, const std::string& contact_extra = "") {
  char text[2048];
  std::snprintf(text, sizeof text, R"([scene]
name = "strip_impact"
gravity = [0, 0]
[solver]
integrator = "verlet"
dt = %.17g
end_time = %.17g
output_interval = 2e-6
[[body]]
name = "striker"
mass = %.17g
inertia = 1.0
position = [-0.050001, 0]
velocity = [1.0, 0]
shape = { type = "box", width = 0.1, height = 0.1 }
[[flex_body]]
name = "strip"
shape = { type = "box", center = [0.5, 0], width = 1.0, height = 0.05 }
grid_spacing = 0.01
thickness = 0.02
fracture = false
[flex_body.material]
youngs_modulus = 200e9
density = 7850
[[probe]]
name = "striker"
body = "striker"
point = [0, 0]
[[contact]]
name = "impact"
type = "rigid_particles"
body = "striker"
flex_body = "strip"
)",
                dt, end_time, mass);
  return std::string(text) + contact_extra;
}

// Writes `text` to `dir/name` and returns the path.
inline std::string write_scene(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace periflex::test

namespace periflex::test {

// Two elastic discs of radius `radius` (dx = 1 mm, E = 100 MPa, rho = 1000 kg/m^3: wave speed
// 316 m/s) thrown at each other at 5 m/s each along a line 2 mm off their centres, one spacing
// apart, with particle contact between them (and within each). No gravity, Verlet.
inline std::string discs_scene(double radius, double dt, double end_time, const std::string& contact_extra = "") {
  char text[2048];
  const double gap = 1e-3;
  std::snprintf(text, sizeof text, R"([scene]
name = "discs"
gravity = [0, 0]
[solver]
integrator = "verlet"
dt = %.17g
end_time = %.17g
[[flex_body]]
name = "left"
shape = { type = "circle", center = [%.17g, 0.001], radius = %.17g }
grid_spacing = 0.001
thickness = 0.01
fracture = false
velocity = [5, 0]
[flex_body.material]
youngs_modulus = 1e8
density = 1000
[[flex_body]]
name = "right"
shape = { type = "circle", center = [%.17g, -0.001], radius = %.17g }
grid_spacing = 0.001
thickness = 0.01
fracture = false
velocity = [-5, 0]
[flex_body.material]
youngs_modulus = 1e8
density = 1000
[[contact]]
name = "touch"
type = "particles"
flex_bodies = ["left", "right"]
)",
                dt, end_time, -radius - 0.5 * gap, radius, radius + 0.5 * gap, radius);
  return std::string(text) + contact_extra;
}

}  // namespace periflex::test
