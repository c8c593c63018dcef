// Small scenes built in C++ for the solver tests (independent of the scene loader).
#pragma once

#include <string>

#include "scene/scene_def.h"

namespace periflex::test {

inline BodyDef body(const std::string& name, double mass, double inertia, Vec2 position, double angle = 0.0) {
  BodyDef b;
  b.name = name;
  b.mass = mass;
  b.inertia = inertia;
  b.position = position;
  b.angle = angle;
  return b;
}

inline JointDef revolute(const std::string& name, const std::string& i, const std::string& j, Vec2 point_i,
                         Vec2 point_j) {
  JointDef d;
  d.kind = JointDef::Kind::kRevolute;
  d.name = name;
  d.body_i = i;
  d.body_j = j;
  d.point_i = point_i;
  d.point_j = point_j;
  return d;
}

inline SceneDef empty_scene(const std::string& integrator, double dt, CorrectionDef::Method method) {
  SceneDef s;
  s.name = "test";
  s.gravity = Vec2(0.0, -9.81);
  s.solver.integrator = integrator;
  s.solver.dt = dt;
  s.solver.correction.method = method;
  return s;
}

// Point mass m on a massless rod of length L pinned to the ground at the origin, released at
// rest from angle theta0 measured from the downward vertical. The body has zero inertia.
inline SceneDef point_pendulum(double length, double theta0, const std::string& integrator, double dt,
                               CorrectionDef::Method method = CorrectionDef::Method::kBaumgarte) {
  SceneDef s = empty_scene(integrator, dt, method);
  const Vec2 bob(length * std::sin(theta0), -length * std::cos(theta0));
  s.bodies.push_back(body("bob", 1.0, 0.0, bob, 0.0));
  // the pin sits at -bob in the body frame (angle 0 at set-up)
  s.joints.push_back(revolute("pivot", "ground", "bob", Vec2::Zero(), -bob));
  return s;
}

// Two uniform bars (mass 1, length 1) hanging from the ground, released horizontal.
inline SceneDef double_pendulum(const std::string& integrator, double dt, CorrectionDef::Method method) {
  SceneDef s = empty_scene(integrator, dt, method);
  const double inertia = 1.0 / 12.0;
  s.bodies.push_back(body("upper", 1.0, inertia, Vec2(0.5, 0.0)));
  s.bodies.push_back(body("lower", 1.0, inertia, Vec2(1.5, 0.0)));
  s.joints.push_back(revolute("shoulder", "ground", "upper", Vec2::Zero(), Vec2(-0.5, 0.0)));
  s.joints.push_back(revolute("elbow", "upper", "lower", Vec2(0.5, 0.0), Vec2(-0.5, 0.0)));
  return s;
}


// A small elastic plate (1 cm square, 1 mm spacing), drifting at 0.1 m/s without gravity, so the
// explicit stability bound applies to every live change.
inline SceneDef small_plate(double dt) {
  SceneDef scene = empty_scene("verlet", dt, CorrectionDef::Method::kNone);
  scene.gravity = Vec2::Zero();
  FlexBodyDef plate;
  plate.name = "plate";
  plate.shape.kind = ShapeDef::Kind::kBox;
  plate.shape.width = plate.shape.height = 0.01;
  plate.grid_spacing = 1e-3;
  plate.thickness = 1e-3;
  plate.material.youngs_modulus = 1e9;
  plate.material.density = 1000.0;
  plate.material.critical_stretch = 0.01;
  plate.velocity = Vec2(0.1, 0.0);
  scene.flex_bodies.push_back(plate);
  return scene;
}

}  // namespace periflex::test
