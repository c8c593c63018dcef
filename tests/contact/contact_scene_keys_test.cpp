// [[contact]] as a user writes it: bad keys are refused with file:line:column and key (exit 2),
// a good one is checked and run, series.csv gains the contact columns, and a scene without
// contact shows no trace of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../cli/run_program.h"
#include "contact_scenes.h"

namespace periflex {
namespace {

using testing::fresh_directory;
using testing::read_text;
using testing::run_periflex;

const std::string kStriker = test::strip_scene(15.7, 1.1e-6, 4e-4);

// `periflex check` on the striker scene with `contact_extra` in its [[contact]] table.
testing::ProgramResult check_with(const std::string& name, const std::string& contact_extra) {
  const auto dir = fresh_directory("contact_keys_" + name);
  return run_periflex("check " + test::write_scene(dir, "scene.toml", test::strip_scene(15.7, 1.1e-6, 4e-4,
                                                                                       contact_extra)));
}

TEST(ContactSceneKeys, BadContactKeysAreRefusedAtTheirLineWithExitTwo) {
  struct Case {
    std::string name, extra, expected;
  };
  // the [[contact]] table starts at line 29 of the scene; its keys follow it
  const Case cases[] = {
      {"unknown", "stifness = 1e6\n", ":34:1: key 'contact.impact.stifness': unknown key 'stifness'"},
      {"restitution", "restitution = 1.5\n", ":34:15: key 'contact.impact.restitution': restitution must be in (0, 1]"},
      {"negative_stiffness", "stiffness = -1\n", "contact.impact.stiffness"},
      {"not_for_rigid", "distance_ratio = 0.8\n", "does not apply to a rigid_particles contact"},
  };
  for (const Case& c : cases) {
    const auto result = check_with(c.name, c.extra);
    EXPECT_EQ(result.exit_code, 2) << c.name << ": " << result.output;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << c.name << ": " << result.output;
  }
}

TEST(ContactSceneKeys, ContactWithAShapelessBodyOrAnUndeclaredFlexBodyIsRefused) {
  const auto dir = fresh_directory("contact_keys_refs");
  std::string shapeless = kStriker;
  shapeless.replace(shapeless.find("shape = { type = \"box\", width = 0.1"), 0, "# ");
  auto result = run_periflex("check " + test::write_scene(dir, "shapeless.toml", shapeless));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(":32:8: key 'contact.impact.body': body 'striker' has no shape to touch"), std::string::npos)
      << result.output;

  std::string unknown = kStriker;
  unknown.replace(unknown.rfind("flex_body = \"strip\""), 19, "flex_body = \"plate\"");
  result = run_periflex("check " + test::write_scene(dir, "unknown.toml", unknown));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(":33:13: key 'contact.impact.flex_body': flexible body 'plate' is not declared"), std::string::npos)
      << result.output;

  const std::string particles = kStriker + "[[contact]]\nname = \"faces\"\ntype = \"particles\"\n"
                                           "flex_bodies = [\"strip\", \"strip\"]\n";
  result = run_periflex("check " + test::write_scene(dir, "twice.toml", particles));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(":37:25: key 'contact.faces.flex_bodies[1]': flexible body 'strip' is listed twice"),
            std::string::npos)
      << result.output;
}

TEST(ContactSceneKeys, RunWritesContactColumnsAndCheckListsTheModule) {
  const auto dir = fresh_directory("contact_run");
  const std::string path = test::write_scene(dir, "scene.toml", kStriker);
  const auto check = run_periflex("check " + path);
  ASSERT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("active modules        rigid_bodies, pd_forces, contact"), std::string::npos)
      << check.output;

  const auto run = run_periflex("run " + path + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::istringstream series(read_text(dir / "out" / "series.csv"));
  std::string header, line;
  std::getline(series, header);
  ASSERT_NE(header.find(",contact_force_total,contact_count"), std::string::npos) << header;
  // column of contact_force_total
  const long force_column = std::count(header.begin(), header.begin() + header.find(",contact_force_total"), ',') + 1;
  // some row has the whole 5-particle face in contact and a force of the order of Z V0 = 40 kN
  bool touching = false;
  while (std::getline(series, line)) {
    std::vector<double> values;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) values.push_back(std::stod(cell));
    const double force = values.at(force_column), count = values.at(force_column + 1);
    if (count == 5 && force > 2e4 && force < 6e4) touching = true;
  }
  EXPECT_TRUE(touching);
}

TEST(ContactSceneKeys, SceneWithoutContactHasNoContactColumnsOrModule) {
  const auto dir = fresh_directory("contact_none");
  std::string none = kStriker.substr(0, kStriker.find("[[contact]]"));
  const std::string path = test::write_scene(dir, "scene.toml", none);
  const auto check = run_periflex("check " + path);
  ASSERT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("active modules        rigid_bodies, pd_forces\n"), std::string::npos) << check.output;
  const auto run = run_periflex("run " + path + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string series = read_text(dir / "out" / "series.csv");
  EXPECT_EQ(series.substr(0, series.find('\n')).find("contact"), std::string::npos);
}

// The critical time step `check` prints, in seconds.
double printed_critical_step(const std::string& output) {
  const auto at = output.find("critical time step");
  return at == std::string::npos ? 0.0 : std::stod(output.substr(output.find_first_of("0123456789", at)));
}

TEST(ContactSceneKeys, CheckPrintsTheCriticalStepWithTheContactStiffnessAdded) {
  // the bonds' bound alone (no contact) and with the default contact stiffness
  // k = 15 c V^2 / delta on the lightest particle: 1 / dt^2 = 1 / dt_bonds^2 + k / (2 m)
  const auto dir = fresh_directory("contact_critical");
  const std::string none = kStriker.substr(0, kStriker.find("[[contact]]"));
  const double bonds = printed_critical_step(run_periflex("check " + test::write_scene(dir, "none.toml", none)).output);
  const double with = printed_critical_step(run_periflex("check " + test::write_scene(dir, "with.toml", kStriker)).output);
  ASSERT_GT(bonds, 0.0);
  const double e = 200e9, t = 0.02, dx = 0.01, delta = 3 * dx, rho = 7850.0, volume = dx * dx * t;
  const double c = 9.0 * e / (3.14159265358979323846 * t * delta * delta * delta);
  const double k = 15.0 * c * volume * volume / delta, m = rho * volume;
  const double expected = 1.0 / std::sqrt(1.0 / (bonds * bonds) + k / (2.0 * m));
  EXPECT_NEAR(with / expected, 1.0, 1e-5) << with << " vs " << expected;
  EXPECT_LT(with, 0.95 * bonds);
}

TEST(ContactSceneKeys, CheckWarnsOfBodiesThatStartOverlapping) {
  // the striker's face 3 mm into the strip: the first column of five particles (0.5 dx deep
  // at 5 mm) is inside the margin; a face 1 um short of the surface touches nothing
  const auto dir = fresh_directory("contact_overlap");
  std::string overlapping = kStriker;
  overlapping.replace(overlapping.find("position = [-0.050001, 0]"), 25, "position = [-0.047, 0]   ");
  const auto check = run_periflex("check " + test::write_scene(dir, "overlap.toml", overlapping));
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("contact 'impact': 5 contact(s) active at t = 0"), std::string::npos) << check.output;
  const auto clear = run_periflex("check " + test::write_scene(dir, "clear.toml", kStriker));
  EXPECT_EQ(clear.output.find("active at t = 0"), std::string::npos) << clear.output;
}

TEST(ContactSceneKeys, StiffnessThatMakesTheStepUnstableIsRefusedUpFront) {
  // dt = 1.3 us is within 0.8 of the bonds' 1.94 us bound but not of the bound with a contact
  // 100 times stiffer than the default
  const auto dir = fresh_directory("contact_unstable");
  const std::string path =
      test::write_scene(dir, "scene.toml", test::strip_scene(15.7, 1.3e-6, 4e-4, "stiffness = 1e11\n"));
  // check refuses it as run does
  const auto check = run_periflex("check " + path);
  EXPECT_EQ(check.exit_code, 2) << check.output;
  const auto run = run_periflex("run " + path + " --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(":34:13: key 'contact.impact.stiffness': contact stiffness 1e+11 N/m lowers the critical step"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("lower the stiffness below about"), std::string::npos) << run.output;
  // the remedy it names works
  const auto at = run.output.find("below about ") + 12;
  const double stable = std::stod(run.output.substr(at));
  const std::string fixed = test::write_scene(
      dir, "fixed.toml", test::strip_scene(15.7, 1.3e-6, 4e-4, "stiffness = " + std::to_string(0.95 * stable) + "\n"));
  const auto again = run_periflex("run " + fixed + " --out " + (dir / "out2").string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

}  // namespace
}  // namespace periflex
