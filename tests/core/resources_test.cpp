// find_resource_root's order: an installed program's own share/periflex first, then
// $PERIFLEX_ROOT, then the source tree.
#include "core/resources.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace periflex {
namespace {

namespace fs = std::filesystem;

// a fresh folder under the test's temporary directory
fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("periflex_resources_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// a folder that looks like a resource root: it holds shaders/
fs::path resource_folder(const fs::path& where) {
  fs::create_directories(where / "shaders");
  return where;
}

TEST(ResourceRoot, InstalledProgramFindsShareBesideItsBinFolder) {
  const fs::path prefix = fresh_folder("installed");
  fs::create_directories(prefix / "bin");
  resource_folder(prefix / "share" / "periflex");
  const fs::path source = resource_folder(fresh_folder("installed_source"));
  const fs::path env = resource_folder(fresh_folder("installed_env"));
  EXPECT_EQ(pick_resource_root((prefix / "bin" / "periflex").string(), env.string(), source.string()),
            (prefix / "share" / "periflex").string());
}

TEST(ResourceRoot, BuildTreeProgramUsesTheVariableThenTheSourceTree) {
  const fs::path build = fresh_folder("build_tree");
  fs::create_directories(build / "src");
  const std::string program = (build / "src" / "periflex").string();
  const fs::path source = resource_folder(fresh_folder("build_source"));
  const fs::path env = resource_folder(fresh_folder("build_env"));
  EXPECT_EQ(pick_resource_root(program, env.string(), source.string()), env.string());
  EXPECT_EQ(pick_resource_root(program, "", source.string()), source.string());
}

TEST(ResourceRoot, VariableWithoutShadersIsPassedOverForTheSourceTree) {
  const fs::path source = resource_folder(fresh_folder("passed_source"));
  const fs::path empty = fresh_folder("passed_empty");
  EXPECT_EQ(pick_resource_root("", empty.string(), source.string()), source.string());
}

TEST(ResourceRoot, NothingFoundNamesTheVariableTheUserSet) {
  const fs::path empty = fresh_folder("nothing_env");
  const fs::path gone = fresh_folder("nothing_source") / "missing";
  EXPECT_EQ(pick_resource_root("", empty.string(), gone.string()), empty.string());
  EXPECT_EQ(pick_resource_root("", "", gone.string()), gone.string());
}

TEST(ResourceRoot, ThisBuildTreeProgramFindsTheSourceTree) {
  // the test program itself runs from the build tree: no share/periflex beside it
  if (std::getenv("PERIFLEX_ROOT") != nullptr) GTEST_SKIP() << "PERIFLEX_ROOT is set";
  EXPECT_EQ(find_resource_root(), std::string(PERIFLEX_SOURCE_ROOT));
}

}  // namespace
}  // namespace periflex
