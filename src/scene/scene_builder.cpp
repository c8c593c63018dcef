#include "scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "scene/contact_reader.h"
#include "scene/file_shape_reader.h"
#include "scene/function_reader.h"
#include "scene/material_law_keys.h"
#include "scene/scene_loader.h"
#include "scene/shape_reader.h"

namespace periflex {

namespace {

using Kind = ShapeDef::Kind;

// Keys of every variant of a typed table, for "does not apply to" messages.
const std::set<std::string> kJointKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "axis_i",
                                          "axis_j", "length", "offset", "relative_angle"};
const std::set<std::string> kDriverKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "axis", "function"};
const std::set<std::string> kForceKeys = {"name", "type", "body_i", "body_j", "point_i", "point_j", "stiffness",
                                          "damping", "free_length", "free_angle", "actuator", "direction", "magnitude"};
const std::set<std::string> kLoadKeys = {"name", "type", "region", "fx", "fy"};

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k) out += (k ? ", " : "") + words[k];
  return out;
}

// Turns a TOML tree into a SceneDef, one section at a time.
class SceneBuilder {
 public:
  SceneBuilder(const ReadContext& context, const toml::table& root)
      : context_(context), top_(context, root, "", "the scene file") {}

  SceneDef build(const std::string& default_name) {
    // the model sections first, so that references can be resolved as they are read
    read_scene(default_name);
    read_solver();
    read_limits();
    for (const auto& [table, index] : elements("body")) scene_.bodies.push_back(read_body(*table, index));
    for (const auto& [table, index] : elements("flex_body")) scene_.flex_bodies.push_back(read_flex_body(*table, index));
    for (const auto& [table, index] : elements("joint")) scene_.joints.push_back(read_joint(*table, index));
    for (const auto& [table, index] : elements("driver")) scene_.drivers.push_back(read_driver(*table, index));
    for (const auto& [table, index] : elements("force")) scene_.forces.push_back(read_force(*table, index));
    for (const auto& [table, index] : elements("probe")) scene_.probes.push_back(read_probe(*table, index));
    for (const auto& [table, index] : elements("attachment"))
      scene_.attachments.push_back(read_attachment(*table, index));
    for (const auto& [table, index] : elements("contact")) scene_.contacts.push_back(read_contact(*table, index));
    top_.finish();

    // a scene needs something that moves
    if (scene_.bodies.empty() && scene_.flex_bodies.empty()) {
      SourceLocation where = context_.locate(nullptr, "body");
      where.line = 1;
      throw InputError(where, "the scene declares no [[body]] and no [[flex_body]]; a scene needs at least one");
    }
    return scene_;
  }

 private:
  // ---------------------------------------------------------------------------
  // Element lists and names

  // The tables of the array of tables `key` (e.g. every [[body]]), with their indices.
  std::vector<std::pair<const toml::table*, size_t>> elements(const std::string& key) {
    std::vector<std::pair<const toml::table*, size_t>> out;
    const toml::node* node = top_.node(key);
    if (node == nullptr) return out;
    const auto* array = node->as_array();
    if (array == nullptr)
      context_.fail(node, key, "expected [[" + key + "]] (an array of tables), found " + describe_type(*node));
    for (size_t k = 0; k < array->size(); ++k) {
      const toml::node* element = array->get(k);
      if (!element->is_table())
        context_.fail(element, key, "expected [[" + key + "]] tables, found " + describe_type(*element));
      out.emplace_back(element->as_table(), k);
    }
    return out;
  }

  // The required, well-formed, per-kind unique name of an element of [[kind]].
  std::string element_name(const toml::table& table, const std::string& kind, size_t index,
                           std::map<std::string, int>& seen) {
    const std::string path = kind + "." + std::to_string(index);
    const toml::node* node = table.get("name");
    if (node == nullptr)
      context_.fail(&table, path + ".name", "missing required key 'name' in [[" + kind + "]] number " +
                    std::to_string(index + 1));
    const auto* text = node->as_string();
    if (text == nullptr) context_.fail(node, path + ".name", "expected a string, found " + describe_type(*node));
    const std::string name = text->get();
    // names appear in override paths and output columns: no dots, no spaces
    const bool plain = !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
      return c == '.' || c == '=' || c == '"' || c == ',' || static_cast<unsigned char>(c) <= ' ';
    });
    if (!plain)
      context_.fail(node, path + ".name", "name '" + name + "' must be non-empty without dots, '=', quotes, commas or spaces");
    const auto first = seen.find(name);
    if (first != seen.end())
      context_.fail(node, kind + "." + name + ".name",
                    "duplicate name '" + name + "' (already declared at line " + std::to_string(first->second) + ")");
    seen.emplace(name, static_cast<int>(node->source().begin.line));
    return name;
  }

  // A rigid body (or the ground, when allowed) named by `key`.
  std::string rigid_reference(TableReader& in, const std::string& key, bool allow_ground) {
    const std::string name = in.required_string(key);
    if (name == "ground") {
      if (!allow_ground) in.fail(key, "'ground' cannot be used here: it does not move; name a rigid body");
      return name;
    }
    if (rigid_names_.count(name) != 0) return name;
    if (flex_names_.count(name) != 0)
      in.fail(key, "'" + name + "' is a flexible body; " + key + " must name a rigid body" +
              " (couple a flexible body through an [[attachment]] to a virtual body)");
    const std::string rigid = rigid_list(allow_ground);
    std::string flexible;
    for (const FlexBodyDef& flex : scene_.flex_bodies) flexible += (flexible.empty() ? "" : ", ") + flex.name;
    in.fail(key, "body '" + name + "' is not declared (rigid bodies: " + (rigid.empty() ? std::string("none") : rigid) +
            (flexible.empty() ? std::string() : "; flexible bodies: " + flexible) + ")");
  }

  std::string rigid_list(bool with_ground) const {
    std::vector<std::string> names;
    if (with_ground) names.emplace_back("ground");
    for (const BodyDef& body : scene_.bodies) names.push_back(body.name);
    return join(names);
  }

  // A physical quantity outside the range any material or model has.
  static void check_range(TableReader& in, const char* key, double value, double lo, double hi, const std::string& unit) {
    if (value >= lo && value <= hi) return;
    const std::string u = unit.empty() ? "" : " " + unit;
    in.fail(key, std::string(key) + " = " + format_number(value) + u + " is outside the physically meaningful range [" +
            format_number(lo) + ", " + format_number(hi) + "]" + u);
  }

  // Two-body elements may not connect a body to itself.
  static void check_distinct(TableReader& in, const std::string& a, const std::string& b, const std::string& what) {
    if (a == b) in.fail("body_j", what + " connects '" + a + "' to itself; body_i and body_j must differ");
  }

  // ---------------------------------------------------------------------------
  // [scene] and [solver]

  void read_scene(const std::string& default_name) {
    const toml::table* table = top_.optional_table("scene");
    scene_.name = default_name;
    if (table == nullptr) return;
    TableReader in(context_, *table, "scene", "[scene]");
    scene_.name = in.string("name", default_name);
    if (scene_.name.empty()) in.fail("name", "the scene name may not be empty (omit it to use the file name)");
    // the name titles outputs and (made safe) names the default output folder: one short line
    if (scene_.name.size() > kMaxSceneNameLength)
      in.fail("name", "the scene name has " + std::to_string(scene_.name.size()) + " characters; at most " +
              std::to_string(kMaxSceneNameLength) + " are allowed");
    if (std::any_of(scene_.name.begin(), scene_.name.end(), [](char c) { return static_cast<unsigned char>(c) < ' ' || c == 127; }))
      in.fail("name", "the scene name may not contain control characters (line breaks, tabs, ...)");
    scene_.description = in.string("description", "");
    scene_.gravity = in.vec2("gravity", Vec2(0.0, -9.81));
    in.finish();
  }

  void read_solver() {
    const toml::table* table = top_.optional_table("solver");
    if (table == nullptr) return;
    TableReader in(context_, *table, "solver", "[solver]");
    SolverDef& solver = scene_.solver;
    // values that later checks relate to each other (and to command-line flags) remember where they came from
    for (const char* key : {"integrator", "dt", "end_time", "output_interval", "threads"}) note_origin(in, key);
    solver.integrator = in.choice("integrator", scene_integrator_names(), solver.integrator);
    solver.dt = in.number("dt", solver.dt, Sign::kPositive, true);
    solver.end_time = in.number("end_time", solver.end_time, Sign::kPositive, true);
    if (solver.dt > solver.end_time)
      in.fail(in.has("dt") ? "dt" : "end_time", "dt = " + format_number(solver.dt) + " exceeds end_time = " +
              format_number(solver.end_time) + "; the run would not take a single step");
    solver.rtol = in.number("rtol", solver.rtol, Sign::kPositive);
    solver.atol = in.number("atol", solver.atol, Sign::kPositive);
    solver.output_interval = in.number("output_interval", solver.output_interval, Sign::kNonNegative, true);
    solver.auto_substep = in.boolean("auto_substep", solver.auto_substep);
    solver.dt_safety = in.number("dt_safety", solver.dt_safety, Sign::kPositive);
    if (solver.dt_safety > 1.0)
      in.fail("dt_safety", "must be in (0, 1] (a fraction of the critical step), found " + format_number(solver.dt_safety));
    solver.allow_unstable = in.boolean("allow_unstable", solver.allow_unstable);
    if (solver.allow_unstable && solver.auto_substep)
      in.fail("allow_unstable", "cannot be true with auto_substep = true (sub-steps keep every step stable); "
                                "set one of them");
    solver.threads = static_cast<int>(in.integer("threads", solver.threads, 0));
    // HHT-alpha is unconditionally stable only for alpha in [-1/3, 0]
    solver.hht_alpha = in.number("hht_alpha", solver.hht_alpha);
    if (solver.hht_alpha < -1.0 / 3.0 || solver.hht_alpha > 0.0)
      in.fail("hht_alpha", "must be in [-1/3, 0], found " + format_number(solver.hht_alpha));
    if (const toml::table* correction = in.optional_table("correction")) read_correction(*correction);
    in.finish();
  }

  // Records where the value under `key` of `in` came from (file position or --set).
  void note_origin(TableReader& in, const char* key) {
    if (const toml::node* node = in.table().get(key)) scene_.origin[in.key_path(key)] = context_.locate(node, in.key_path(key));
  }

  // [limits]: budgets raised (or lowered) knowingly
  void read_limits() {
    const toml::table* table = top_.optional_table("limits");
    if (table == nullptr) return;
    TableReader in(context_, *table, "limits", "[limits]");
    LimitsDef& l = scene_.limits;
    for (const char* key : {"max_particles", "max_memory", "max_steps", "max_output_rows", "max_frames",
                            "max_grid_rows", "max_threads"})
      note_origin(in, key);
    l.max_particles = in.number("max_particles", l.max_particles, Sign::kPositive);
    l.max_memory = in.number("max_memory", l.max_memory, Sign::kNonNegative);
    l.max_steps = in.number("max_steps", l.max_steps, Sign::kPositive);
    l.max_output_rows = in.number("max_output_rows", l.max_output_rows, Sign::kPositive);
    l.max_frames = in.number("max_frames", l.max_frames, Sign::kPositive);
    l.max_grid_rows = in.number("max_grid_rows", l.max_grid_rows, Sign::kPositive);
    l.max_threads = static_cast<int>(in.integer("max_threads", l.max_threads, 0));
    // a limit is a count: even raised knowingly it must fit the integers that hold it
    for (const char* key : {"max_particles", "max_steps", "max_output_rows", "max_frames", "max_grid_rows"})
      if (const auto value = in.optional_number(key); value && *value > 1e15)
        in.fail(key, "must be at most 1e15, found " + format_number(*value));
    if (l.max_particles > 2e9) in.fail("max_particles", "must be at most 2e9 (particle indices are 32-bit integers)");
    in.finish();
  }

  void read_correction(const toml::table& table) {
    TableReader in(context_, table, "solver.correction", "[solver.correction]");
    CorrectionDef& c = scene_.solver.correction;
    const std::string method = in.choice("method", {"none", "baumgarte", "projection"}, "baumgarte");
    c.method = method == "none" ? CorrectionDef::Method::kNone
               : method == "projection" ? CorrectionDef::Method::kProjection : CorrectionDef::Method::kBaumgarte;
    c.alpha = in.number("alpha", c.alpha, Sign::kNonNegative);
    c.beta = in.number("beta", c.beta, Sign::kNonNegative);
    c.tolerance = in.number("tolerance", c.tolerance, Sign::kPositive);
    c.max_iterations = static_cast<int>(in.integer("max_iterations", c.max_iterations, 1));
    // each step runs up to this many Newton iterations: a million would stall every step
    if (c.max_iterations > kMaxProjectionIterations)
      in.fail("max_iterations", "must be at most " + std::to_string(kMaxProjectionIterations) + ", found " +
              std::to_string(c.max_iterations) + " (projection converges in a few iterations or not at all)");
    in.finish();
  }

  // ---------------------------------------------------------------------------
  // [[body]]

  BodyDef read_body(const toml::table& table, size_t index) {
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

  // ---------------------------------------------------------------------------
  // [[joint]]

  JointDef read_joint(const toml::table& table, size_t index) {
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

  // ---------------------------------------------------------------------------
  // [[driver]]

  DriverDef read_driver(const toml::table& table, size_t index) {
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

  // ---------------------------------------------------------------------------
  // [[force]]

  ForceDef read_force(const toml::table& table, size_t index) {
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

  // ---------------------------------------------------------------------------
  // [[probe]]

  ProbeDef read_probe(const toml::table& table, size_t index) {
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

  std::string all_body_list() const {
    std::vector<std::string> names;
    for (const BodyDef& body : scene_.bodies) names.push_back(body.name);
    for (const FlexBodyDef& body : scene_.flex_bodies) names.push_back(body.name);
    return join(names);
  }

  // ---------------------------------------------------------------------------
  // [[flex_body]]

  FlexBodyDef read_flex_body(const toml::table& table, size_t index) {
    FlexBodyDef flex;
    flex.name = element_name(table, "flex_body", index, body_names_);
    TableReader in(context_, table, "flex_body." + flex.name, "[[flex_body]] '" + flex.name + "'");
    in.node("name");
    if (flex.name == "ground") in.fail("name", "'ground' is the name of the implicit ground; choose another");
    flex_names_.insert(flex.name);
    flex.where = in.where();

    // geometry: an area filled with particles, minus holes
    const toml::node* shape = in.node("shape");
    if (shape == nullptr) in.fail_missing("shape");
    // a shape from a file (points, image, dxf) is read once grid_spacing, thickness and holes are known
    const bool from_file = is_file_shape(*shape);
    if (!from_file)
      flex.shape = read_shape(context_, *shape, in.key_path("shape"), {Kind::kBox, Kind::kCircle, Kind::kPolygon, Kind::kBoolean});
    if (const toml::node* holes = in.node("holes")) flex.holes = read_shape_list(context_, *holes, in.key_path("holes"), kRegionShapeKinds);

    // grid and horizon
    flex.grid_spacing = in.required_number("grid_spacing", Sign::kPositive, true);
    flex.thickness = in.number("thickness", flex.thickness, Sign::kPositive, true);
    check_range(in, "thickness", flex.thickness, 1e-9, 1e3, "m");
    if (from_file) read_file_shape(context_, *shape, in.key_path("shape"), scene_.limits, flex);
    flex.horizon_ratio = in.number("horizon_ratio", flex.horizon_ratio, Sign::kPositive);
    // the budget names these where they were set, in the file or by --set
    for (const char* key : {"grid_spacing", "horizon_ratio"}) note_origin(in, key);
    if (flex.horizon_ratio < 1.0)
      in.fail("horizon_ratio", "must be at least 1 (a horizon smaller than the grid spacing has no bonds), found " +
              format_number(flex.horizon_ratio));
    if (flex.horizon_ratio > kMaxHorizonRatio)
      in.fail("horizon_ratio", "must be at most " + format_number(kMaxHorizonRatio) +
                                   " (each particle would have hundreds of thousands of bonds), found " +
                                   format_number(flex.horizon_ratio));
    // refuse absurd grids before anything is allocated
    // (a first look from the area; the exact count and the whole scene's budget come after loading)
    const double limit = std::max(kMaxParticlesPerFlexBody, scene_.limits.max_particles);
    const double particles = shape_area(flex.shape) / (flex.grid_spacing * flex.grid_spacing);
    if (!(particles <= limit)) {
      const double smallest = std::sqrt(shape_area(flex.shape) / limit);
      in.fail("grid_spacing", "flexible body '" + flex.name + "' would have about " + format_count(std::round(particles)) +
              " particles (area / grid_spacing^2), more than the limit of " + format_count(limit) +
              " (limits.max_particles); use grid_spacing >= " + format_number(smallest));
    }

    // model options
    const std::string influence = in.choice("influence", {"constant", "conical"}, "constant");
    flex.influence = influence == "conical" ? FlexBodyDef::Influence::kConical : FlexBodyDef::Influence::kConstant;
    flex.partial_volume_correction = in.boolean("partial_volume_correction", flex.partial_volume_correction);
    flex.surface_correction = in.boolean("surface_correction", flex.surface_correction);
    flex.fracture = in.boolean("fracture", flex.fracture);
    flex.bond_damping = in.number("bond_damping", 0.0, Sign::kNonNegative);
    flex.global_damping = in.number("global_damping", 0.0, Sign::kNonNegative);
    flex.velocity = in.vec2("velocity", Vec2::Zero());

    // pre-cracks and unbreakable regions
    if (const toml::array* notches = in.optional_array("notches"))
      for (size_t k = 0; k < notches->size(); ++k) flex.notches.push_back(read_notch(*notches->get(k), in.key_path("notches") + "." + std::to_string(k)));
    const std::string damage = in.choice("damage", {"exclude_notch", "include_notch"}, "exclude_notch");
    flex.damage = damage == "include_notch" ? FlexBodyDef::Damage::kIncludeNotch : FlexBodyDef::Damage::kExcludeNotch;
    if (const toml::node* no_fail = in.node("no_fail"))
      flex.no_fail_regions = read_shape_list(context_, *no_fail, in.key_path("no_fail"), kRegionShapeKinds);

    // material
    const toml::table* material = in.optional_table("material");
    if (material == nullptr) in.fail_missing("material", "a [flex_body.material] table");
    flex.material = read_material(*material, in.key_path("material"), flex.fracture);

    // loads and boundary conditions
    const toml::node* loads = in.node("load");
    if (loads != nullptr) {
      const auto* array = loads->as_array();
      if (array == nullptr)
        context_.fail(loads, in.key_path("load"), "expected [[flex_body.load]] tables, found " + describe_type(*loads));
      std::map<std::string, int> load_names;
      for (size_t k = 0; k < array->size(); ++k) {
        const toml::node* element = array->get(k);
        if (!element->is_table())
          context_.fail(element, in.key_path("load"), "expected [[flex_body.load]] tables, found " + describe_type(*element));
        flex.loads.push_back(read_load(*element->as_table(), k, flex.name, load_names));
      }
    }
    in.finish();
    return flex;
  }

  NotchDef read_notch(const toml::node& node, const std::string& key) {
    const auto* table = node.as_table();
    if (table == nullptr) context_.fail(&node, key, "expected a notch { p1 = [x, y], p2 = [x, y] }, found " + describe_type(node));
    TableReader in(context_, *table, key, "notch '" + key + "'");
    NotchDef notch;
    notch.p1 = in.required_vec2("p1");
    notch.p2 = in.required_vec2("p2");
    if (!((notch.p2 - notch.p1).norm() > 0.0)) in.fail("p2", "a notch needs p1 and p2 to differ");
    in.finish();
    return notch;
  }

  PdMaterialDef read_material(const toml::table& table, const std::string& path, bool fracture) {
    TableReader in(context_, table, path, "[flex_body.material]");
    PdMaterialDef m;
    m.youngs_modulus = in.required_number("youngs_modulus", Sign::kPositive);
    m.density = in.required_number("density", Sign::kPositive);
    // physically meaningful ranges: beyond them the critical step under- or overflows
    check_range(in, "youngs_modulus", m.youngs_modulus, 1e-3, 1e13, "Pa");
    check_range(in, "density", m.density, 1e-3, 1e6, "kg/m^3");
    // one fracture criterion: energy or stretch (the softening law takes both: its area and its peak)
    const auto energy = in.optional_number("fracture_energy", Sign::kPositive);
    const auto stretch = in.optional_number("critical_stretch", Sign::kPositive);
    m.model = read_material_model(in);
    const bool softening = m.model == PdMaterialDef::Model::kBilinearSoftening;
    if (energy && stretch && !softening)
      in.fail("critical_stretch", "give fracture_energy or critical_stretch, not both");
    if (fracture && !energy && !stretch)
      in.fail_missing("fracture_energy", "or critical_stretch; or set fracture = false in the flexible body");
    m.fracture_energy = energy.value_or(0.0);
    m.critical_stretch = stretch.value_or(0.0);
    if (energy) check_range(in, "fracture_energy", *energy, 1e-12, 1e8, "J/m^2");
    if (stretch) check_range(in, "critical_stretch", *stretch, 1e-12, 10.0, "");
    m.plane_strain = in.choice("plane", {"stress", "strain"}, "stress") == "strain";
    if (softening) read_softening_keys(in, m, energy, stretch);
    // the state-based model takes any admissible Poisson ratio: -1 < nu < 1/2, and in plane
    // stress also nu = 1/2 (an incompressible sheet thins instead; its 2D bulk modulus E/(2(1-nu)) stays finite)
    if (m.model == PdMaterialDef::Model::kStateBased) {
      const auto nu = in.optional_number("poisson_ratio");
      if (!nu) in.fail_missing("poisson_ratio", "model = \"state_based\" needs Poisson's ratio");
      const bool inside = m.plane_strain ? (*nu > -1.0 && *nu < 0.5) : (*nu > -1.0 && *nu <= 0.5);
      if (!inside)
        in.fail("poisson_ratio", "poisson_ratio " + format_number(*nu) + " is outside " +
                (m.plane_strain ? "(-1, 0.5) in plane strain (at 0.5 the 2D bulk modulus is infinite)"
                                : "(-1, 0.5] in plane stress"));
      m.poisson_ratio = *nu;
      in.finish();
      return m;
    }
    // bond-based peridynamics fixes Poisson's ratio: 1/3 in plane stress, 1/4 in plane strain
    if (const auto nu = in.optional_number("poisson_ratio")) {
      const double fixed = m.plane_strain ? 0.25 : 1.0 / 3.0;
      if (std::abs(*nu - fixed) > 0.05)
        in.fail("poisson_ratio", "bond-based peridynamics fixes Poisson's ratio at " + format_number(fixed) + " in plane " +
                (m.plane_strain ? "strain" : "stress") + "; " + format_number(*nu) +
                " cannot be represented (remove poisson_ratio or change plane)");
      m.poisson_ratio = *nu;
    }
    in.finish();
    return m;
  }

  RegionLoadDef read_load(const toml::table& table, size_t index, const std::string& flex_name,
                          std::map<std::string, int>& names) {
    RegionLoadDef load;
    const std::string kind = "flex_body." + flex_name + ".load";
    load.name = element_name(table, kind, index, names);
    TableReader in(context_, table, kind + "." + load.name, "[[flex_body.load]] '" + load.name + "'");
    in.node("name");
    load.where = in.where();
    const std::string type =
        in.required_choice("type", {"prescribed_velocity", "prescribed_displacement", "traction", "body_force"});
    load.kind = type == "prescribed_velocity"       ? RegionLoadDef::Kind::kPrescribedVelocity
                : type == "prescribed_displacement" ? RegionLoadDef::Kind::kPrescribedDisplacement
                : type == "traction"                ? RegionLoadDef::Kind::kTraction
                                                    : RegionLoadDef::Kind::kBodyForce;
    const toml::node* region = in.node("region");
    if (region == nullptr) in.fail_missing("region");
    load.region = read_shape(context_, *region, in.key_path("region"), kRegionShapeKinds);
    if (const toml::node* fx = in.node("fx")) load.fx = read_time_function(context_, *fx, in.key_path("fx"));
    if (const toml::node* fy = in.node("fy")) load.fy = read_time_function(context_, *fy, in.key_path("fy"));
    // a load with neither component does nothing
    if (!load.fx && !load.fy) in.fail_missing("fx", "or fy; a load needs at least one component");
    in.finish();
    return load;
  }

  // ---------------------------------------------------------------------------
  // [[attachment]]

  AttachmentDef read_attachment(const toml::table& table, size_t index) {
    AttachmentDef attachment;
    attachment.name = element_name(table, "attachment", index, attachment_names_);
    TableReader in(context_, table, "attachment." + attachment.name, "[[attachment]] '" + attachment.name + "'");
    in.node("name");
    attachment.where = in.where();
    attachment.body = rigid_reference(in, "body", false);
    attachment.flex_body = in.required_string("flex_body");
    if (flex_names_.count(attachment.flex_body) == 0) {
      std::vector<std::string> names;
      for (const FlexBodyDef& flex : scene_.flex_bodies) names.push_back(flex.name);
      in.fail("flex_body", "flexible body '" + attachment.flex_body + "' is not declared (flexible bodies: " +
              (names.empty() ? std::string("none") : join(names)) + ")");
    }
    const toml::node* region = in.node("region");
    if (region == nullptr) in.fail_missing("region");
    attachment.region = read_shape(context_, *region, in.key_path("region"), kRegionShapeKinds);
    in.finish();
    return attachment;
  }

  // ---------------------------------------------------------------------------
  // [[contact]] (the law is read in contact_reader.cpp)

  ContactDef read_contact(const toml::table& table, size_t index) {
    ContactDef contact;
    contact.name = element_name(table, "contact", index, contact_names_);
    TableReader in(context_, table, "contact." + contact.name, "[[contact]] '" + contact.name + "'");
    in.node("name");
    contact.where = in.where();
    contact.kind = read_contact_kind(in);
    if (contact.kind == ContactDef::Kind::kRigidParticles) {
      // the rigid body's drawing shapes are its contact shapes
      contact.body = rigid_reference(in, "body", false);
      const auto body = std::find_if(scene_.bodies.begin(), scene_.bodies.end(),
                                     [&](const BodyDef& b) { return b.name == contact.body; });
      if (body->shapes.empty())
        in.fail("body", "body '" + contact.body + "' has no shape to touch; give it a shape (its drawing shape is "
                        "its contact shape)");
    }
    if (contact.kind == ContactDef::Kind::kRigid) {
      // two rigid bodies, each with a shape
      contact.body = rigid_reference(in, "body_i", false);
      contact.body_j = rigid_reference(in, "body_j", false);
      if (contact.body_j == contact.body) in.fail("body_j", "body_j must differ from body_i ('" + contact.body + "')");
      for (const auto& [key, name] : {std::pair<const char*, std::string>{"body_i", contact.body}, {"body_j", contact.body_j}}) {
        const auto body = std::find_if(scene_.bodies.begin(), scene_.bodies.end(),
                                       [&](const BodyDef& b) { return b.name == name; });
        if (body->shapes.empty())
          in.fail(key, "body '" + name + "' has no shape to touch; give it a shape (its drawing shape is its "
                       "contact shape)");
      }
    }
    read_contact_law(in, flex_names_, contact);
    return contact;
  }

  const ReadContext& context_;
  TableReader top_;
  SceneDef scene_;
  std::set<std::string> rigid_names_, flex_names_;
  std::map<std::string, int> body_names_, joint_names_, driver_names_, force_names_, probe_names_, attachment_names_,
      contact_names_;
};

}  // namespace

SceneDef build_scene(const toml::table& root, const ReadContext& context, const std::string& default_name) {
  SceneBuilder builder(context, root);
  return builder.build(default_name);
}

}  // namespace periflex
