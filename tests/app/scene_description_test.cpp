// The description panel's text: a scene file's opening comment, else its scene.description.
#include "app/scene_description.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace periflex {
namespace {

TEST(SceneDescription, LeadingCommentWithoutHashesRulersOrTheTomlAfterIt) {
  const std::string text =
      "# Notched plate torn by two grips.\n"
      "#\n"
      "# What it teaches:\n"
      "# a crack.\n"
      "# -----------------------------\n"
      "#   indented stays indented\n"
      "\n"
      "[scene]\n"
      "# a comment inside the scene is not part of it\n"
      "name = \"plate\"\n";
  EXPECT_EQ(leading_comment(text), "Notched plate torn by two grips.\n\nWhat it teaches: a crack.\n  indented stays indented");
}

TEST(SceneDescription, NoLeadingCommentGivesTheDescriptionKey) {
  EXPECT_EQ(leading_comment("[scene]\n# late comment\nname = \"x\"\n"), "");
  const auto path = std::filesystem::path(::testing::TempDir()) / "described.toml";
  std::ofstream(path) << "[scene]\nname = \"x\"\ndescription = \"one line\"\n";
  EXPECT_EQ(scene_description(path.string(), "one line"), "one line");
  std::ofstream(path) << "# Said at the top\n[scene]\nname = \"x\"\n";
  EXPECT_EQ(scene_description(path.string(), "one line"), "Said at the top");
}

TEST(SceneDescription, EveryShippedSceneHasOne) {
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(PERIFLEX_SOURCE_ROOT) / "scenes")) {
    if (entry.path().extension() != ".toml") continue;
    EXPECT_FALSE(scene_description(entry.path().string(), "").empty()) << entry.path();
  }
}

}  // namespace
}  // namespace periflex
