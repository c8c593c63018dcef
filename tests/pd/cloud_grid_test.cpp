// A body given particle by particle (its own grid written out as points, in a shuffled order)
// has the particles, bonds and stiffnesses of the body filled from the shape; its file's
// no-fail flags reach the bonds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "pd/cloud_grid.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

ParticleCloud cloud_of(const ParticleGrid& grid, double volume) {
  ParticleCloud c;
  c.x = grid.x;
  c.y = grid.y;
  c.volume.assign(grid.x.size(), volume);
  c.no_fail.assign(grid.x.size(), 0);
  c.line.assign(grid.x.size(), 0);
  c.source = "test";
  return c;
}

TEST(CloudGrid, GridWrittenAsPointsBuildsTheSameBonds) {
  FlexBodyDef shape_def = test::glass_plate(0.01, 0.006, 5e-4);
  ShapeDef hole;
  hole.kind = ShapeDef::Kind::kCircle;
  hole.radius = 0.0015;
  shape_def.holes.push_back(hole);
  const auto from_shape = PdBody::build(shape_def, 0);

  FlexBodyDef cloud_def = shape_def;
  cloud_def.particles = std::make_shared<const ParticleCloud>(
      cloud_of(fill_grid(shape_def.shape, shape_def.holes, 5e-4), 5e-4 * 5e-4 * shape_def.thickness));
  const auto from_cloud = PdBody::build(cloud_def, 0);

  ASSERT_EQ(from_cloud->particle_count(), from_shape->particle_count());
  EXPECT_EQ(from_cloud->reference_positions(), from_shape->reference_positions());
  EXPECT_EQ(from_cloud->volumes(), from_shape->volumes());
  const BondStore& a = from_shape->bonds();
  const BondStore& b = from_cloud->bonds();
  EXPECT_EQ(a.row, b.row);
  EXPECT_EQ(a.neighbor, b.neighbor);
  EXPECT_EQ(a.length_class, b.length_class);
  EXPECT_EQ(a.coefficient, b.coefficient);
  EXPECT_EQ(from_cloud->critical_time_step(), from_shape->critical_time_step());
}

// Shuffled points keep their order as particles; each particle keeps its own neighbours.
TEST(CloudGrid, ShuffledPointsKeepTheirNeighbours) {
  const FlexBodyDef shape_def = test::glass_plate(0.006, 0.004, 5e-4);
  const auto from_shape = PdBody::build(shape_def, 0);
  ParticleGrid grid = fill_grid(shape_def.shape, {}, 5e-4);
  std::vector<int> order(grid.size());
  for (int i = 0; i < grid.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  ParticleGrid shuffled = grid;
  for (int k = 0; k < grid.size(); ++k) {
    shuffled.x[k] = grid.x[order[k]];
    shuffled.y[k] = grid.y[order[k]];
  }
  FlexBodyDef cloud_def = shape_def;
  cloud_def.particles = std::make_shared<const ParticleCloud>(cloud_of(shuffled, 5e-4 * 5e-4 * shape_def.thickness));
  const auto from_cloud = PdBody::build(cloud_def, 0);
  const BondStore& a = from_shape->bonds();
  const BondStore& b = from_cloud->bonds();
  ASSERT_EQ(a.directed_count(), b.directed_count());
  for (int k = 0; k < grid.size(); ++k) {
    const int i = order[k];
    ASSERT_EQ(a.row[i + 1] - a.row[i], b.row[k + 1] - b.row[k]) << k;
    std::vector<int> na, nb;
    for (int64_t q = a.row[i]; q < a.row[i + 1]; ++q) na.push_back(a.neighbor[q]);
    for (int64_t q = b.row[k]; q < b.row[k + 1]; ++q) nb.push_back(order[b.neighbor[q]]);
    std::sort(nb.begin(), nb.end());
    EXPECT_EQ(na, nb) << k;
  }
}

TEST(CloudGrid, FlaggedPointsNeverBreak) {
  FlexBodyDef def = test::glass_plate(0.004, 0.004, 5e-4);
  ParticleCloud cloud = cloud_of(fill_grid(def.shape, {}, 5e-4), 5e-4 * 5e-4 * def.thickness);
  cloud.no_fail[3] = 1;
  def.particles = std::make_shared<const ParticleCloud>(cloud);
  const std::vector<uint8_t> flags = body_no_fail(def, body_particles(def));
  EXPECT_EQ(std::count(flags.begin(), flags.end(), 1), 1);
  EXPECT_EQ(flags[3], 1);
  // stretched by half: every bond breaks but those of the flagged particle
  const auto body = PdBody::build(def, 0);
  body->update_fracture(test::affine_positions(*body, 0.5 * Eigen::Matrix2d::Identity()));
  std::vector<float> damage;
  body->damage(damage);
  EXPECT_EQ(damage[3], 0.0f);
  EXPECT_GT(damage[0], 0.5f);
}

}  // namespace
}  // namespace periflex
