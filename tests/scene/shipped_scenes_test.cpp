// Every scene shipped in scenes/ loads, and its initial configuration is consistent:
// revolute joints closed and angle drivers matching the initial angles. The folder is
// globbed at test time, so scenes added later are covered too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

namespace periflex {
namespace {

// The scenes offered to users: scenes/*.toml. Subfolders (scenes/stability/, ...) hold case files
// of other suites, some of them invalid on purpose, and are not walked.
std::vector<std::string> shipped_scenes() {
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(PERIFLEX_SOURCE_ROOT) / "scenes"))
    if (entry.path().extension() == ".toml") paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// Global position of a body-fixed point (ground points are global).
Vec2 global_point(const SceneDef& scene, const std::string& body, const Vec2& local) {
  if (body == "ground") return local;
  for (const BodyDef& b : scene.bodies)
    if (b.name == body) return b.position + rotation(b.angle) * local;
  ADD_FAILURE() << "no body " << body;
  return Vec2::Zero();
}

double body_angle(const SceneDef& scene, const std::string& body) {
  for (const BodyDef& b : scene.bodies)
    if (b.name == body) return b.angle;
  return 0.0;
}

TEST(ShippedScenes, FolderHoldsTheFourRigidScenes) {
  std::vector<std::string> stems;
  for (const std::string& path : shipped_scenes()) stems.push_back(std::filesystem::path(path).stem().string());
  for (const char* expected : {"pendulum", "double_pendulum", "slider_crank", "four_bar"})
    EXPECT_NE(std::find(stems.begin(), stems.end(), expected), stems.end()) << expected;
}

TEST(ShippedScenes, EverySceneLoads) {
  for (const std::string& path : shipped_scenes()) {
    SCOPED_TRACE(path);
    SceneDef scene;
    try {
      scene = load_scene(path);
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    EXPECT_FALSE(scene.bodies.empty() && scene.flex_bodies.empty());
    EXPECT_EQ(scene.path, path);
    EXPECT_FALSE(scene.name.empty());
    EXPECT_GT(scene.solver.end_time, 0.0);
  }
}

// Positions in the files are typed by hand; a revolute joint that is not closed at t = 0
// would be silently pulled shut by the solver's initial projection.
TEST(ShippedScenes, RevoluteJointsAreClosedInitially) {
  for (const std::string& path : shipped_scenes()) {
    SCOPED_TRACE(path);
    const SceneDef scene = load_scene(path);
    for (const JointDef& joint : scene.joints) {
      if (joint.kind != JointDef::Kind::kRevolute && joint.kind != JointDef::Kind::kRigid) continue;
      const Vec2 pi = global_point(scene, joint.body_i, joint.point_i);
      const Vec2 pj = global_point(scene, joint.body_j, joint.point_j);
      // 1e-9 m: the files give positions to 15 significant digits
      EXPECT_LT((pi - pj).norm(), 1e-9) << joint.name;
    }
  }
}

TEST(ShippedScenes, RevoluteRevoluteLengthsMatchInitialPositions) {
  for (const std::string& path : shipped_scenes()) {
    SCOPED_TRACE(path);
    const SceneDef scene = load_scene(path);
    for (const JointDef& joint : scene.joints) {
      if (joint.kind != JointDef::Kind::kRevoluteRevolute || joint.length_from_initial) continue;
      const Vec2 pi = global_point(scene, joint.body_i, joint.point_i);
      const Vec2 pj = global_point(scene, joint.body_j, joint.point_j);
      EXPECT_NEAR((pi - pj).norm(), joint.length, 1e-9) << joint.name;
    }
  }
}

TEST(ShippedScenes, AngleDriversStartAtTheInitialAngles) {
  for (const std::string& path : shipped_scenes()) {
    SCOPED_TRACE(path);
    const SceneDef scene = load_scene(path);
    for (const DriverDef& driver : scene.drivers) {
      if (driver.kind != DriverDef::Kind::kAbsoluteAngle) continue;
      // 1e-12 rad: both are typed to 16 digits
      EXPECT_NEAR(driver.function(0.0), body_angle(scene, driver.body_i), 1e-12) << driver.name;
    }
  }
}

// The four-bar must really be a Grashof crank-rocker: s + l <= p + q with the crank shortest.
TEST(ShippedScenes, FourBarIsGrashofCrankRocker) {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/four_bar.toml");
  std::map<std::string, Vec2> pins;
  for (const JointDef& joint : scene.joints) pins[joint.name] = global_point(scene, joint.body_i, joint.point_i);
  ASSERT_EQ(pins.size(), 4u);
  const double ground = (pins["o4"] - pins["o2"]).norm();
  const double crank = (pins["a"] - pins["o2"]).norm();
  const double coupler = (pins["b"] - pins["a"]).norm();
  const double rocker = (pins["b"] - pins["o4"]).norm();
  std::vector<double> links = {ground, crank, coupler, rocker};
  std::sort(links.begin(), links.end());
  EXPECT_LE(links[0] + links[3], links[1] + links[2]);
  EXPECT_DOUBLE_EQ(crank, links[0]);
}

// The example closing docs/scenes.md must stay a valid scene, and the documented override
// examples must apply to the shipped scene they name.
TEST(SceneDocs, ExampleAndOverridesInTheDocumentationWork) {
  std::ifstream in(std::string(PERIFLEX_SOURCE_ROOT) + "/docs/scenes.md");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const size_t start = doc.rfind("```toml\n");
  ASSERT_NE(start, std::string::npos);
  const size_t end = doc.find("```", start + 8);
  ASSERT_NE(end, std::string::npos);
  const SceneDef scene = parse_scene(doc.substr(start + 8, end - start - 8), "docs/scenes.md");
  EXPECT_EQ(scene.name, "bar_pendulum");
  ASSERT_EQ(scene.joints.size(), 1u);
  EXPECT_EQ(scene.joints[0].body_j, "bar");

  const SceneDef four_bar = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/four_bar.toml",
                                       {"solver.dt=1e-4", "scene.gravity=[0,-1.62]", "body.crank.mass=2",
                                        "driver.motor.function.rate=10", "solver.integrator=verlet"});
  EXPECT_DOUBLE_EQ(four_bar.solver.dt, 1e-4);
  EXPECT_DOUBLE_EQ(four_bar.gravity.y(), -1.62);
  EXPECT_DOUBLE_EQ(four_bar.bodies[0].mass, 2.0);
  EXPECT_DOUBLE_EQ(four_bar.drivers[0].function.rate, 10.0);
  EXPECT_EQ(four_bar.solver.integrator, "verlet");
}

}  // namespace
}  // namespace periflex
