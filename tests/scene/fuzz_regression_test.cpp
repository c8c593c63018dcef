// Inputs the scene-parser fuzzer once broke (tests/data/scenes/fuzz/, kept by
// scripts/fuzz-scene-parser.sh) must now either load or be refused with InputError. Leading
// "#set key=value" lines are passed as overrides, as the fuzz target does.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/scene_loader.h"

namespace periflex {
namespace {

TEST(FuzzRegressions, EveryKeptInputLoadsOrIsRefused) {
  const std::filesystem::path folder = std::filesystem::path(PERIFLEX_TEST_DATA) / "scenes" / "fuzz";
  if (!std::filesystem::exists(folder)) GTEST_SKIP() << "no fuzz findings kept";
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    // overrides as the fuzz target reads them
    std::vector<std::string> overrides;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line) && line.rfind("#set ", 0) == 0;) overrides.push_back(line.substr(5));
    try {
      parse_scene(text, entry.path().string(), overrides);
    } catch (const InputError& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
    }
  }
}

// The fuzzer's override seed is itself a valid scene whose overrides all apply.
TEST(FuzzRegressions, OverrideSeedLoadsWithItsOverrides) {
  const std::filesystem::path seed = std::filesystem::path(PERIFLEX_SOURCE_ROOT) / "fuzz" / "seeds" / "overrides.toml";
  std::ifstream in(seed);
  ASSERT_TRUE(in.good());
  std::vector<std::string> overrides;
  std::stringstream all;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#set ", 0) == 0) overrides.push_back(line.substr(5));
    all << line << '\n';
  }
  ASSERT_EQ(overrides.size(), 6u);
  const SceneDef scene = parse_scene(all.str(), seed.string(), overrides);
  EXPECT_DOUBLE_EQ(scene.solver.dt, 1e-4);
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass, 2.0);
  EXPECT_DOUBLE_EQ(scene.flex_bodies[0].material.youngs_modulus, 1e9);
  EXPECT_EQ(scene.drivers[0].function.values, (std::vector<double>{0.0, 2.0}));
  ASSERT_TRUE(scene.flex_bodies[0].loads[0].fy.has_value());
  EXPECT_EQ(scene.flex_bodies[0].loads[0].fy->kind, TimeFunction::Kind::kHarmonic);
}

}  // namespace
}  // namespace periflex
