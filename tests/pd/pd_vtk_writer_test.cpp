// The particle writer for ParaView (src/output/vtk_writer): structure and values of the .vtu.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "output/vtk_writer.h"

namespace periflex {
namespace {

Snapshot three_particles() {
  auto geometry = std::make_shared<SceneGeometry>();
  geometry->reference_x = {0.0f, 1.0f, 2.0f};
  geometry->reference_y = {0.0f, 0.0f, 0.0f};
  Snapshot s;
  s.geometry = geometry;
  s.time = 1.25e-5;
  s.px = {0.5f, 1.0f, 2.0f};
  s.py = {0.0f, 0.25f, 0.0f};
  s.damage = {0.0f, 0.5f, 1.0f};
  s.displacement = {0.5f, 0.25f, 0.0f};
  s.speed = {3.0f, 2.0f, 1.0f};
  s.vx = {3.0f, 0.0f, -1.0f};
  s.vy = {0.0f, 2.0f, 0.0f};
  s.strain = {0.0f, 0.001f, 0.0f};
  return s;
}

// The whitespace-separated values of the DataArray named `name`.
std::vector<std::string> array_values(const std::string& doc, const std::string& name) {
  const size_t at = doc.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  const size_t open = doc.find('>', at) + 1, close = doc.find("</DataArray>", open);
  std::istringstream in(doc.substr(open, close - open));
  std::vector<std::string> values;
  for (std::string v; in >> v;) values.push_back(v);
  return values;
}

TEST(VtkWriter, ParticlesBecomeVertexCellsWithPointData) {
  const std::string doc = vtu_document(three_particles());
  EXPECT_NE(doc.find("NumberOfPoints=\"3\" NumberOfCells=\"3\""), std::string::npos);
  EXPECT_EQ(array_values(doc, "position"), (std::vector<std::string>{"0.5", "0", "0", "1", "0.25", "0", "2", "0", "0"}));
  // displacement vector = position - reference
  EXPECT_EQ(array_values(doc, "displacement"),
            (std::vector<std::string>{"0.5", "0", "0", "0", "0.25", "0", "0", "0", "0"}));
  EXPECT_EQ(array_values(doc, "damage"), (std::vector<std::string>{"0", "0.5", "1"}));
  EXPECT_EQ(array_values(doc, "speed"), (std::vector<std::string>{"3", "2", "1"}));
  EXPECT_EQ(array_values(doc, "velocity"),
            (std::vector<std::string>{"3", "0", "0", "0", "2", "0", "-1", "0", "0"}));
  EXPECT_EQ(array_values(doc, "connectivity"), (std::vector<std::string>{"0", "1", "2"}));
  EXPECT_EQ(array_values(doc, "offsets"), (std::vector<std::string>{"1", "2", "3"}));
  EXPECT_EQ(array_values(doc, "types"), (std::vector<std::string>{"1", "1", "1"}));  // VTK_VERTEX
  EXPECT_EQ(array_values(doc, "TIME"), (std::vector<std::string>{"1.25e-05"}));
}

TEST(VtkWriter, WritesCompleteFileAndLeavesNoTemporary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "periflex_vtk_writer_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "particles_000000.vtu").string();
  write_vtu(path, three_particles());
  std::ifstream in(path);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), vtu_document(three_particles()));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().extension(), ".vtu") << entry.path();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace periflex
