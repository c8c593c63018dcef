// A scene's flexible bodies written as a point file read back as the very same particles.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "output/point_file_writer.h"
#include "pd/cloud_grid.h"
#include "scene/point_file_reader.h"

namespace periflex {
namespace {

FlexBodyDef plate(const std::string& name, Vec2 center, double dx) {
  FlexBodyDef def;
  def.name = name;
  def.shape.kind = ShapeDef::Kind::kCircle;
  def.shape.center = center;
  def.shape.radius = 0.01;
  def.grid_spacing = dx;
  def.thickness = 3e-3;
  ShapeDef strip;
  strip.kind = ShapeDef::Kind::kBox;
  strip.center = center + Vec2(0, 0.008);
  strip.width = 0.02;
  strip.height = 0.004;
  def.no_fail_regions.push_back(strip);
  return def;
}

TEST(PointFileWriter, BodiesReadBackBitForBitByBlock) {
  SceneDef scene;
  scene.name = "two";
  scene.flex_bodies = {plate("a", Vec2(0.1, 0.2), 1.0 / 3.0 * 1e-3), plate("b", Vec2(-0.3, 0.7), 7e-4)};
  const auto path = std::filesystem::temp_directory_path() / "periflex_points_out.csv";
  write_point_file(path.string(), scene);
  for (size_t b = 0; b < 2; ++b) {
    const FlexBodyDef& def = scene.flex_bodies[b];
    const ParticleGrid grid = body_particles(def);
    const std::vector<uint8_t> no_fail = body_no_fail(def, grid);
    PointFileOptions options;
    options.block = static_cast<long>(b) + 1;
    const ParticleCloud back = read_point_file(path.string(), options);
    ASSERT_EQ(back.size(), grid.size());
    long flagged = 0;
    for (int i = 0; i < grid.size(); ++i) {
      ASSERT_EQ(back.x[i], grid.x[i]);
      ASSERT_EQ(back.y[i], grid.y[i]);
      ASSERT_EQ(back.volume[i], def.grid_spacing * def.grid_spacing * def.thickness);
      ASSERT_EQ(back.no_fail[i], no_fail[i]);
      flagged += no_fail[i];
    }
    EXPECT_GT(flagged, 0);  // the strip's particles carry their flag through the file
  }
}

// A body read from a graded point file (volumes of its own) is written with those volumes, each
// read back as the same double.
TEST(PointFileWriter, VolumesOfAGradedFileAreWrittenAsGiven) {
  auto cloud = std::make_shared<ParticleCloud>();
  const double dx = 1e-3, t = 2e-3;
  for (int k = 0; k < 6; ++k) {
    const double h = k < 3 ? dx : 0.5 * dx;
    cloud->x.push_back(k * 0.7 * dx);
    cloud->y.push_back(0.1 * k * dx);
    cloud->volume.push_back(h * h * t * (1.0 + 0.1 / 3.0 * k));
    cloud->no_fail.push_back(0);
  }
  SceneDef scene;
  scene.name = "graded";
  FlexBodyDef def;
  def.name = "g";
  def.grid_spacing = dx;
  def.thickness = t;
  def.particles = cloud;
  scene.flex_bodies = {def};
  const auto path = std::filesystem::temp_directory_path() / "periflex_points_graded.csv";
  write_point_file(path.string(), scene);
  const ParticleCloud back = read_point_file(path.string(), {});
  ASSERT_EQ(back.size(), cloud->size());
  EXPECT_EQ(back.volume, cloud->volume);
  EXPECT_EQ(back.x, cloud->x);
}

}  // namespace
}  // namespace periflex
