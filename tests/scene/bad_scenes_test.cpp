// Malformed scenes are refused with an InputError that names the file (or "--set"), the line
// and the dotted key of the problem. Each case is a file in tests/data/scenes/bad/; the table
// below gives, from reading that file, the line and key that a user should be sent to.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

namespace periflex {
namespace {

const std::string kData = std::string(PERIFLEX_TEST_DATA) + "/scenes";

struct BadCase {
  const char* file;      // in tests/data/scenes/bad/
  int line;              // where the problem is (1-based)
  const char* key;       // substring of the dotted key ("" when the error is not about a key)
  const char* message;   // substring of the message
};

const BadCase kBadCases[] = {
    {"syntax_error.toml", 5, "", "TOML syntax error"},  // the unclosed array meets 'mass' on line 5
    {"wrong_type.toml", 4, "body.arm.mass", "expected a number, found a string"},
    {"unknown_key.toml", 4, "body.crank.masss", "unknown key 'masss' in [[body]] 'crank'; expected one of:"},
    {"missing_body.toml", 12, "joint.pin.body_j", "body 'rod' is not declared"},
    {"negative_mass.toml", 4, "body.arm.mass", "must not be negative"},
    {"negative_inertia.toml", 5, "body.arm.inertia", "must not be negative"},
    {"nan_position.toml", 4, "body.bob.position", "finite"},
    {"inf_time_step.toml", 3, "solver.dt", "finite"},
    {"empty.toml", 1, "body", "at least one"},
    {"comments_only.toml", 1, "body", "at least one"},
    {"huge_number.toml", 4, "body.arm.position", "absurdly large"},
    {"duplicate_body_names.toml", 9, "body.arm.name", "duplicate name 'arm' (already declared at line 3)"},
    {"duplicate_across_kinds.toml", 6, "flex_body.plate.name", "duplicate name 'plate'"},
    {"duplicate_joint_names.toml", 15, "joint.pin.name", "duplicate name 'pin'"},
    {"joint_to_itself.toml", 12, "joint.pin.body_j", "to itself"},
    {"unknown_joint_type.toml", 10, "joint.pin.type", "unknown type 'hinge'"},
    {"inapplicable_joint_key.toml", 13, "joint.pin.axis_i", "does not apply to a revolute joint"},
    {"table_times_not_increasing.toml", 12, "driver.spin.function.times", "strictly increase"},
    {"unknown_function_type.toml", 12, "driver.spin.function.type", "unknown type 'exponential'"},
    {"too_many_particles.toml", 5, "flex_body.plate.grid_spacing", "about 10000000000 particles"},
    {"ground_declared.toml", 3, "body.ground.name", "implicit"},
    {"zero_time_step.toml", 3, "solver.dt", "must be positive"},
    {"negative_end_time.toml", 4, "solver.end_time", "must be positive"},
    {"unknown_integrator.toml", 3, "solver.integrator", "unknown integrator 'euler_forward'"},
    {"unknown_correction.toml", 3, "solver.correction.method", "unknown method 'magic'"},
    {"empty_polygon.toml", 4, "body.arm.shape.vertices", "at least 3 vertices"},
    {"unknown_shape.toml", 4, "body.arm.shape.type", "unknown type 'triangle'"},
    {"zero_axis.toml", 13, "joint.slide.axis_i", "zero-length axis"},
    {"horizon_ratio_below_one.toml", 6, "flex_body.plate.horizon_ratio", "at least 1"},
    {"zero_grid_spacing.toml", 5, "flex_body.plate.grid_spacing", "must be positive"},
    {"unknown_load_type.toml", 12, "flex_body.plate.load.top.type", "unknown type 'pressure'"},
    {"unknown_force_type.toml", 10, "force.push.type", "unknown type 'impulse'"},
    {"unknown_driver_type.toml", 10, "driver.spin.type", "unknown type 'absolute_speed'"},
    {"probe_missing_body.toml", 10, "probe.tip.body", "body 'arn' is not declared"},
    {"attachment_missing_flex_body.toml", 11, "attachment.hold.flex_body", "flexible body 'plate' is not declared"},
    {"joint_to_flex_body.toml", 15, "joint.pin.body_j", "'plate' is a flexible body"},
    {"body_not_array_of_tables.toml", 2, "body", "expected [[body]] (an array of tables), found a table"},
    {"gravity_three_components.toml", 3, "scene.gravity", "found 3 elements"},
    {"missing_material.toml", 2, "flex_body.plate.material", "missing required key 'material'"},
    {"float_threads.toml", 3, "solver.threads", "expected an integer"},
    {"hht_alpha_out_of_range.toml", 4, "solver.hht_alpha", "must be in [-1/3, 0]"},
    {"allow_unstable_with_auto_substep.toml", 4, "solver.allow_unstable", "cannot be true with auto_substep = true"},
    {"allow_unstable_not_boolean.toml", 3, "solver.allow_unstable", "expected a boolean"},
    {"missing_joint_name.toml", 8, "joint.0.name", "missing required key 'name'"},
    {"state_based_nu_half_plane_strain.toml", 12, "flex_body.plate.material.poisson_ratio", "outside (-1, 0.5) in plane strain"},
    {"state_based_nu_above_half_plane_stress.toml", 11, "flex_body.plate.material.poisson_ratio", "outside (-1, 0.5] in plane stress"},
    {"state_based_without_poisson_ratio.toml", 6, "flex_body.plate.material.poisson_ratio", "missing required key 'poisson_ratio'"},
    {"unknown_pd_model.toml", 10, "flex_body.plate.material.model", "correspondence"},
    {"softening_without_ratio.toml", 6, "flex_body.plate.material.softening_ratio", "missing required key 'softening_ratio'"},
    {"softening_ratio_and_critical_stretch.toml", 12, "flex_body.plate.material.softening_ratio", "not both"},
    {"softening_ratio_one.toml", 11, "flex_body.plate.material.softening_ratio", "outside (1, 1000]"},
};

TEST(BadScenes, EachIsRefusedAtTheRightLineAndKey) {
  for (const BadCase& c : kBadCases) {
    const std::string path = kData + "/bad/" + c.file;
    SCOPED_TRACE(path);
    try {
      load_scene(path);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.where().file, path) << what;
      EXPECT_EQ(e.where().line, c.line) << what;
      EXPECT_NE(e.where().key.find(c.key), std::string::npos) << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << what;
      // the printed message leads with file:line so editors can jump to it
      EXPECT_EQ(what.rfind(path + ":" + std::to_string(c.line) + ":", 0), 0u) << what;
    }
  }
}

// A new bad file without an entry in the table would test nothing.
TEST(BadScenes, EveryFileInTheFolderHasAnExpectation) {
  std::set<std::string> listed;
  for (const BadCase& c : kBadCases) listed.insert(c.file);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kData + "/bad")) {
    ++files;
    EXPECT_EQ(listed.count(entry.path().filename().string()), 1u) << entry.path();
  }
  EXPECT_EQ(files, static_cast<int>(std::size(kBadCases)));
  EXPECT_GE(files, 20);
}

// A file that cannot be read is bad input too.
TEST(BadScenes, MissingFileIsAnInputError) {
  const std::string path = kData + "/bad/no_such_file.toml";
  try {
    load_scene(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------
// Bad overrides on a valid scene: located at "--set", naming the override and its key path.

struct BadOverride {
  const char* text;
  const char* key;
  const char* message;
};

const BadOverride kBadOverrides[] = {
    {"body.nobody.mass=2", "body.nobody.mass", "no element named 'nobody' in 'body' (names: crank)"},
    {"solver.dt=abc[", "solver.dt", "is not a TOML value"},
    {"solver.dt=\"fast\"", "solver.dt", "expected a number, found a string"},
    {"solver.dtt=1", "solver.dtt", "unknown key 'dtt' in [solver]"},
    {"body.crank.mass=-2", "body.crank.mass", "must not be negative"},
    {"solver.dt", "", "expected key.path=value"},
    {"solver.dt=", "solver.dt", "no value"},
    {"driver.crank_speed.function.rate=nan", "driver.crank_speed.function.rate", "finite"},
    {"joint.pin.type=hinge", "joint.pin.type", "unknown type 'hinge'"},
    {"solver.dt.x=1", "solver.dt.x", "'solver.dt' is a floating-point number, not a table"},
    {"scene.gravity=[0,-1.62,3]", "scene.gravity", "found 3 elements"},
    {"body=1", "body", "cannot replace the whole 'body' array"},
    {"flex_body.plate.grid_spacing=1e-3", "flex_body.plate.grid_spacing", "declares no [[flex_body]]"},
    {"body.7.mass=1", "body.7.mass", "index 7 is beyond the 1 elements"},
    {"solver..dt=1", "solver..dt", "empty segment"},
    {"joint.pin.length=0.3", "joint.pin.length", "does not apply to a revolute joint"},
    {"solver.dt=1\nend_time = 5", "solver.dt", "not a single TOML value"},
};

TEST(BadOverrides, EachIsRefusedNamingTheOverride) {
  const std::string base = kData + "/override_base.toml";
  for (const BadOverride& c : kBadOverrides) {
    SCOPED_TRACE(c.text);
    try {
      load_scene(base, {c.text});
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.where().file, "--set") << what;
      EXPECT_EQ(e.where().line, 0) << what;
      EXPECT_NE(e.where().key.find(c.key), std::string::npos) << what;
      EXPECT_NE(what.find(std::string("override '") + c.text + "'"), std::string::npos) << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace periflex
