// The rigid mechanism's sections: [[body]], [[joint]], [[driver]], [[force]] and [[probe]], each
// element's keys checked against its type.
#include "scene/scene_table_reader.h"

#include <algorithm>
#include <cmath>

#include "scene/function_reader.h"
#include "scene/shape_reader.h"

namespace periflex {

namespace {

using scene_tables::join;

// Keys of every variant of a typed table, for "does not apply to" messages.
const std::set<std::string> kJointKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "axis_i",
                                          "axis_j", "length", "offset", "relative_angle"};
const std::set<std::string> kDriverKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "axis", "function"};
const std::set<std::string> kForceKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "stiffness",
                                          "damping", "free_length", "free_angle", "actuator", "direction", "magnitude"};

}  // namespace

BodyDef SceneTableReader::read_body(const toml::table& table, size_t index) {
  BodyDef body;
  body.name = element_name(table, "body", index, body_names_);
  TableReader in(context_, table, "body." + body.name, "[[body]] '" + body.name + "'");
  in.node("name");
  if (body.name == "ground")
    in.fail("name", "'ground' is implicit and may not be declared; give ground points in global coordinates");
  rigid_names_.insert(body.name);
  body.where = in.where();
  body.is_virtual = in.boolean("virtual", false);

  // zero mass or inertia is fine where the constraints determine the motion (a point mass on a
  // rod, a massless link); the model set-up names a body whose motion they leave undetermined
  body.mass = in.number("mass", body.mass);
  body.inertia = in.number("inertia", body.inertia);
  for (const char* key : {"mass", "inertia"}) {
    const double value = std::string(key) == "mass" ? body.mass : body.inertia;
    if (value < 0.0) in.fail(key, std::string(key) + " must not be negative, found " + format_number(value));
  }

  body.position = in.vec2("position", Vec2::Zero());
  body.angle = in.number("angle", 0.0);
  body.velocity = in.vec2("velocity", Vec2::Zero());
  body.angular_velocity = in.number("angular_velocity", 0.0);

  // drawing: one shape or a list of them
  const toml::node* shape = in.node("shape");
  const toml::node* shapes = in.node("shapes");
  if (shape != nullptr && shapes != nullptr) in.fail("shapes", "give either shape or shapes, not both");
  if (shape != nullptr) body.shapes.push_back(read_shape(context_, *shape, in.key_path("shape")));
  if (shapes != nullptr) body.shapes = read_shape_list(context_, *shapes, in.key_path("shapes"));
  in.finish();
  return body;
}

JointDef SceneTableReader::read_joint(const toml::table& table, size_t index) {
  JointDef joint;
  joint.name = element_name(table, "joint", index, joint_names_);
  TableReader in(context_, table, "joint." + joint.name, "[[joint]] '" + joint.name + "'");
  in.node("name");
  joint.where = in.where();
  const std::string type = in.required_choice(
      "type", {"revolute", "translational", "rigid", "revolute_revolute", "revolute_translational"});
  joint.body_i = rigid_reference(in, "body_i", true);
  joint.body_j = rigid_reference(in, "body_j", true);
  check_distinct(in, joint.body_i, joint.body_j, "joint '" + joint.name + "'");
  joint.point_i = in.vec2("point_i", Vec2::Zero());
  joint.point_j = in.vec2("point_j", Vec2::Zero());

  // type-specific keys
  if (type == "revolute") {
    joint.kind = JointDef::Kind::kRevolute;
  } else if (type == "translational") {
    joint.kind = JointDef::Kind::kTranslational;
    joint.axis_i = in.axis("axis_i", Vec2::UnitX());
    joint.axis_j = in.axis("axis_j", Vec2::UnitX());
  } else if (type == "rigid") {
    joint.kind = JointDef::Kind::kRigid;
    if (const auto angle = in.optional_number("relative_angle")) {
      joint.relative_angle = *angle;
      joint.relative_angle_from_initial = false;
    }
  } else if (type == "revolute_revolute") {
    joint.kind = JointDef::Kind::kRevoluteRevolute;
    joint.length = -1.0;
    if (const auto length = in.optional_number("length", Sign::kPositive, true)) {
      joint.length = *length;
      joint.length_from_initial = false;
    }
  } else {
    joint.kind = JointDef::Kind::kRevoluteTranslational;
    joint.axis_i = in.axis("axis_i", Vec2::UnitX());
    joint.axis_j = in.axis("axis_j", Vec2::UnitX());
    joint.offset = in.number("offset", 0.0, Sign::kAny, true);
  }
  in.finish(kJointKeys, "a " + type + " joint");
  return joint;
}

DriverDef SceneTableReader::read_driver(const toml::table& table, size_t index) {
  DriverDef driver;
  driver.name = element_name(table, "driver", index, driver_names_);
  TableReader in(context_, table, "driver." + driver.name, "[[driver]] '" + driver.name + "'");
  in.node("name");
  driver.where = in.where();
  const std::string type =
      in.required_choice("type", {"absolute_angle", "relative_angle", "absolute_position", "relative_position"});
  const bool relative = type.rfind("relative", 0) == 0;
  const bool position = type.find("position") != std::string::npos;
  driver.kind = type == "absolute_angle"      ? DriverDef::Kind::kAbsoluteAngle
                : type == "relative_angle"    ? DriverDef::Kind::kRelativeAngle
                : type == "absolute_position" ? DriverDef::Kind::kAbsolutePosition
                                              : DriverDef::Kind::kRelativePosition;

  // an absolute driver moves one body; a relative one measures j against i
  driver.body_i = rigid_reference(in, "body_i", relative);
  if (relative) {
    driver.body_j = rigid_reference(in, "body_j", true);
    check_distinct(in, driver.body_i, driver.body_j, "driver '" + driver.name + "'");
  }
  if (position) {
    driver.point_i = in.vec2("point_i", Vec2::Zero());
    if (relative) driver.point_j = in.vec2("point_j", Vec2::Zero());
    driver.axis = in.axis("axis", Vec2::UnitX());
  }
  const toml::node* function = in.node("function");
  if (function == nullptr) in.fail_missing("function");
  driver.function = read_time_function(context_, *function, in.key_path("function"));
  in.finish(kDriverKeys, "a " + type + " driver");
  return driver;
}

ForceDef SceneTableReader::read_force(const toml::table& table, size_t index) {
  ForceDef force;
  force.name = element_name(table, "force", index, force_names_);
  TableReader in(context_, table, "force." + force.name, "[[force]] '" + force.name + "'");
  in.node("name");
  force.where = in.where();
  const std::string type = in.required_choice("type", {"spring_damper", "rotational_spring", "force", "torque"});
  const bool two_bodies = type == "spring_damper" || type == "rotational_spring";

  // spring elements join two bodies (either may be the ground); loads act on one body
  force.body_i = rigid_reference(in, "body_i", two_bodies);
  if (two_bodies) {
    force.body_j = rigid_reference(in, "body_j", true);
    check_distinct(in, force.body_i, force.body_j, "force '" + force.name + "'");
    force.stiffness = in.number("stiffness", 0.0, Sign::kNonNegative);
    force.damping = in.number("damping", 0.0, Sign::kNonNegative);
  }
  auto function_or = [&](const char* key, const TimeFunction& fallback) {
    const toml::node* node = in.node(key);
    return node != nullptr ? read_time_function(context_, *node, in.key_path(key)) : fallback;
  };

  if (type == "spring_damper") {
    force.kind = ForceDef::Kind::kSpringDamper;
    force.point_i = in.vec2("point_i", Vec2::Zero());
    force.point_j = in.vec2("point_j", Vec2::Zero());
    force.free_length = in.number("free_length", -1.0, Sign::kNonNegative, true);
    force.actuator = function_or("actuator", TimeFunction::constant(0.0));
  } else if (type == "rotational_spring") {
    force.kind = ForceDef::Kind::kRotationalSpring;
    if (const auto angle = in.optional_number("free_angle")) {
      force.free_angle = *angle;
      force.free_angle_from_initial = false;
    }
  } else {
    force.kind = type == "force" ? ForceDef::Kind::kForce : ForceDef::Kind::kTorque;
    if (type == "force") {
      force.point_i = in.vec2("point_i", Vec2::Zero());
      force.direction = in.axis("direction", Vec2::UnitX());
    }
    if (!in.has("magnitude")) {
      in.node("magnitude");
      in.fail_missing("magnitude");
    }
    force.magnitude = function_or("magnitude", TimeFunction::constant(0.0));
  }
  in.finish(kForceKeys, "a " + type + " force");
  return force;
}

ProbeDef SceneTableReader::read_probe(const toml::table& table, size_t index) {
  ProbeDef probe;
  probe.name = element_name(table, "probe", index, probe_names_);
  TableReader in(context_, table, "probe." + probe.name, "[[probe]] '" + probe.name + "'");
  in.node("name");
  probe.where = in.where();
  // a rigid body point or the particle of a flexible body nearest a reference point
  probe.body = in.required_string("body");
  if (probe.body == "ground") in.fail("body", "a probe on the ground would never move; name a body");
  if (rigid_names_.count(probe.body) == 0 && flex_names_.count(probe.body) == 0)
    in.fail("body", "body '" + probe.body + "' is not declared (bodies: " + all_body_list() + ")");
  probe.point = in.vec2("point", Vec2::Zero());
  in.finish();
  return probe;
}

std::string SceneTableReader::all_body_list() const {
  std::vector<std::string> names;
  for (const BodyDef& body : scene_.bodies) names.push_back(body.name);
  for (const FlexBodyDef& body : scene_.flex_bodies) names.push_back(body.name);
  return join(names);
}

}  // namespace periflex
