// Inputs the scene-parser fuzzer once broke (tests/data/scenes/fuzz/, kept by
// scripts/fuzz-scene-parser.sh) and the hostile corpus it starts from must now either load (with
// the scene's budget checked and its warnings computed) or be refused with InputError. Leading
// "#set key=value" lines are passed as overrides, as the fuzz target does.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "scene/scene_warnings.h"

namespace periflex {
namespace {

// Loads `file` as the fuzz target does: parse, budget, warnings; only InputError may come out.
void load_like_the_fuzzer(const std::filesystem::path& file) {
  SCOPED_TRACE(file.string());
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  // overrides as the fuzz target reads them
  std::vector<std::string> overrides;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line) && line.rfind("#set ", 0) == 0;) overrides.push_back(line.substr(5));
  try {
    const SceneDef scene = parse_scene(text, file.string(), overrides);
    check_scene_budget(scene);
    scene_warnings(scene);
  } catch (const InputError& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
  }
}

std::vector<std::filesystem::path> toml_files(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::exists(folder)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == ".toml") files.push_back(entry.path());
  return files;
}

// The kept findings: an empty folder means the regression test tests nothing, which is a failure.
TEST(FuzzRegressions, EveryKeptInputLoadsOrIsRefused) {
  const auto files = toml_files(std::filesystem::path(PERIFLEX_TEST_DATA) / "scenes" / "fuzz");
  ASSERT_FALSE(files.empty()) << "tests/data/scenes/fuzz holds no inputs";
  for (const auto& file : files) load_like_the_fuzzer(file);
}

// The fuzzer starts from the hostile-input corpus; each of its scenes loads or is refused the same way.
TEST(FuzzRegressions, EveryHostileSeedLoadsOrIsRefused) {
  const auto files = toml_files(std::filesystem::path(PERIFLEX_TEST_DATA) / "hostile" / "scenes");
  ASSERT_GE(files.size(), 50u);
  for (const auto& file : files) load_like_the_fuzzer(file);
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
