// The VTK writer (src/io/vtk_writer): the structure of the .vtu and .vtp documents and the
// values in their binary appended block, read back as a VTK reader reads them.
#include "io/vtk_writer.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "io/vtk_series.h"

namespace periflex {
namespace {

Snapshot three_particles() {
  auto geometry = std::make_shared<SceneGeometry>();
  geometry->reference_x = {0.0f, 1.0f, 2.0f};
  geometry->reference_y = {0.0f, 0.0f, 0.0f};
  geometry->reference_xy = {0.0, 0.0, 1.0, 0.0, 2.0, 0.0};
  geometry->particle_volume = {1e-9, 2e-9, 3e-9};
  geometry->flex_bodies = {{"a", 0, 2, 1.0}, {"b", 2, 1, 1.0}};
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
  // full precision: a displacement of 1e-12 m that float positions cannot hold
  s.full_precision = true;
  s.particle_q = {0.5, 0.0, 1.0, 0.25, 2.0 + 1e-12, 0.0};
  s.particle_qd = {3.0, 0.0, 0.0, 2.0, -1.0, 0.0};
  return s;
}

// The values of the DataArray named `name`, as a reader finds them: the offset in the XML, then
// a UInt64 byte count and the raw values in the appended block after its '_'.
template <typename T>
std::vector<T> array_values(const std::string& doc, const std::string& name) {
  const size_t at = doc.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  if (at == std::string::npos) return {};
  const size_t key = doc.find("offset=\"", at) + 8;
  const size_t offset = std::stoull(doc.substr(key, doc.find('"', key) - key));
  const size_t base = doc.find("<AppendedData encoding=\"raw\">");
  EXPECT_NE(base, std::string::npos);
  const size_t start = doc.find('_', base) + 1 + offset;
  uint64_t bytes = 0;
  std::memcpy(&bytes, doc.data() + start, sizeof bytes);
  EXPECT_EQ(bytes % sizeof(T), 0u) << name;
  std::vector<T> values(bytes / sizeof(T));
  std::memcpy(values.data(), doc.data() + start + sizeof bytes, bytes);
  return values;
}

TEST(VtkWriter, ParticlesBecomeVertexCellsWithFullPrecisionPointData) {
  const std::string doc = vtu_document(three_particles());
  EXPECT_NE(doc.find("NumberOfPoints=\"3\" NumberOfCells=\"3\""), std::string::npos);
  EXPECT_NE(doc.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_EQ(array_values<double>(doc, "position"),
            (std::vector<double>{0.5, 0.0, 0.0, 1.0, 0.25, 0.0, 2.0 + 1e-12, 0.0, 0.0}));
  // displacement = position - reference, in doubles: the 1e-12 survives
  const std::vector<double> u = array_values<double>(doc, "displacement");
  ASSERT_EQ(u.size(), 9u);
  EXPECT_EQ(u[0], 0.5);
  EXPECT_EQ(u[4], 0.25);
  EXPECT_NEAR(u[6], 1e-12, 1e-15);
  EXPECT_GT(u[6], 0.0);
  EXPECT_EQ(array_values<float>(doc, "damage"), (std::vector<float>{0.0f, 0.5f, 1.0f}));
  EXPECT_EQ(array_values<double>(doc, "speed"), (std::vector<double>{3.0, 2.0, 1.0}));
  EXPECT_EQ(array_values<double>(doc, "velocity"),
            (std::vector<double>{3.0, 0.0, 0.0, 0.0, 2.0, 0.0, -1.0, 0.0, 0.0}));
  EXPECT_EQ(array_values<double>(doc, "volume"), (std::vector<double>{1e-9, 2e-9, 3e-9}));
  EXPECT_EQ(array_values<int32_t>(doc, "body"), (std::vector<int32_t>{0, 0, 1}));
  EXPECT_EQ(array_values<int64_t>(doc, "connectivity"), (std::vector<int64_t>{0, 1, 2}));
  EXPECT_EQ(array_values<int64_t>(doc, "offsets"), (std::vector<int64_t>{1, 2, 3}));
  EXPECT_EQ(array_values<uint8_t>(doc, "types"), (std::vector<uint8_t>{1, 1, 1}));  // VTK_VERTEX
  EXPECT_NE(doc.find(">1.2500000000000001e-05</DataArray>"), std::string::npos);  // TIME, every digit
}

TEST(VtkWriter, RigidBodiesBecomePolygonsAtTheirPose) {
  auto geometry = std::make_shared<SceneGeometry>();
  SceneGeometry::Body ground{"ground", true, false, {}};
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.width = 2.0;
  box.height = 1.0;
  geometry->bodies = {ground, {"crank", false, true, {box}}};
  Snapshot s;
  s.geometry = geometry;
  s.bodies = {{}, {10.0, 5.0, 1.5707963267948966}};
  const std::string doc = vtp_bodies_document(s);
  EXPECT_NE(doc.find("NumberOfPoints=\"4\""), std::string::npos);
  EXPECT_NE(doc.find("NumberOfPolys=\"1\""), std::string::npos);
  // the box's corner (-1, -0.5) turned a quarter and moved to (10, 5): (10.5, 4)
  const std::vector<double> points = array_values<double>(doc, "points");
  ASSERT_EQ(points.size(), 12u);
  EXPECT_NEAR(points[0], 10.5, 1e-12);
  EXPECT_NEAR(points[1], 4.0, 1e-12);
  EXPECT_EQ(array_values<int64_t>(doc, "offsets"), (std::vector<int64_t>{4}));
  EXPECT_EQ(array_values<int32_t>(doc, "body"), (std::vector<int32_t>{1}));
  EXPECT_EQ(array_values<uint8_t>(doc, "virtual"), (std::vector<uint8_t>{1}));
  EXPECT_EQ(array_values<double>(doc, "angle"), (std::vector<double>{1.5707963267948966}));
}

TEST(VtkWriter, WritesCompleteFileAndLeavesNoTemporary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("periflex_vtk_writer_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "particles_000000.vtu").string();
  write_vtu(path, three_particles());
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), vtu_document(three_particles()));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().extension(), ".vtu") << entry.path();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace periflex
