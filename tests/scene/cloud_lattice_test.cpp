// Points of a file placed against the body's grid: the indices follow the positions, points off
// the grid make a cloud off it (each with its nearest node), and two coincident points or a
// volume far from the grid cell's are refused naming the line.
#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/cloud_lattice.h"

namespace periflex {
namespace {

ParticleCloud cloud(const std::vector<Vec2>& points, double volume) {
  ParticleCloud c;
  for (size_t k = 0; k < points.size(); ++k) {
    c.x.push_back(points[k].x());
    c.y.push_back(points[k].y());
    c.volume.push_back(volume);
    c.no_fail.push_back(0);
    c.line.push_back(static_cast<long>(k) + 10);
  }
  return c;
}

int error_line(const ParticleCloud& c, double dx, double t, std::string* message = nullptr) {
  try {
    place_on_lattice(c, dx, t, "f.csv");
  } catch (const InputError& e) {
    if (message) *message = e.what();
    return e.where().line;
  }
  return -1;
}

TEST(CloudLattice, GridPointsGetTheirIndices) {
  const double dx = 1.0 / 3.0;
  const ParticleCloud c = cloud({{0.5 + 2 * dx, -1.0}, {0.5, -1.0 + dx}, {0.5 + dx, -1.0 + 3 * dx}}, dx * dx * 2.0);
  const CloudLattice l = place_on_lattice(c, dx, 2.0, "f.csv");
  EXPECT_EQ(l.origin, Vec2(0.5, -1.0));
  EXPECT_EQ(l.ix, (std::vector<int32_t>{2, 0, 1}));
  EXPECT_EQ(l.iy, (std::vector<int32_t>{0, 1, 3}));
}

TEST(CloudLattice, GridPointsAreOnTheGrid) {
  EXPECT_TRUE(place_on_lattice(cloud({{0, 0}, {1, 0}, {2, 1 + 1e-8}}, 1.0), 1.0, 1.0, "f.csv").on_grid);
}

TEST(CloudLattice, PointOffTheGridMakesACloudOffItWithTheNearestNodes) {
  const CloudLattice l = place_on_lattice(cloud({{0, 0}, {1, 0}, {2.4, 1}, {2.6, 1}}, 1.0), 1.0, 1.0, "f.csv");
  EXPECT_FALSE(l.on_grid);
  EXPECT_EQ(l.ix, (std::vector<int32_t>{0, 1, 2, 3}));
  EXPECT_EQ(l.iy, (std::vector<int32_t>{0, 0, 1, 1}));
}

// Off the grid, points a hundredth of a spacing apart are two particles; closer than the
// tolerance they are one point given twice, found across nodes (2.4999999 and 2.5 round apart).
TEST(CloudLattice, OffTheGridOnlyPointsWithinTheToleranceCoincide) {
  EXPECT_EQ(error_line(cloud({{0, 0}, {1.3, 0}, {1.31, 0}}, 1.0), 1.0, 1.0), -1);
  std::string message;
  EXPECT_EQ(error_line(cloud({{0, 0}, {2.5, 0.2}, {1.3, 0}, {2.4999999, 0.2}}, 1.0), 1.0, 1.0, &message), 13);
  EXPECT_NE(message.find("coincides with the point of line 11 (closer than"), std::string::npos) << message;
}

TEST(CloudLattice, CoincidentPointsNameBothLines) {
  std::string message;
  EXPECT_EQ(error_line(cloud({{0, 0}, {1, 0}, {2, 0}, {1, 1e-9}}, 1.0), 1.0, 1.0, &message), 13);
  EXPECT_NE(message.find("coincides with the point of line 11"), std::string::npos) << message;
}

// Volumes other than the grid cell's (a graded mesh) are kept; one a thousand times off (a file
// in the wrong unit) is refused naming its line.
TEST(CloudLattice, VolumesOfTheirOwnAreKeptAndAVolumeFarOffNamesItsLine) {
  ParticleCloud c = cloud({{0, 0}, {1, 0}}, 2.0);
  EXPECT_TRUE(place_on_lattice(c, 1.0, 2.0, "f.csv").cell_volumes);
  c.volume[1] = 2.5;
  EXPECT_FALSE(place_on_lattice(c, 1.0, 2.0, "f.csv").cell_volumes);
  c.volume[1] = 2.0 * 1.01e3;
  std::string message;
  EXPECT_EQ(error_line(c, 1.0, 2.0, &message), 11);
  EXPECT_NE(message.find("1010 times grid_spacing^2 x thickness"), std::string::npos) << message;
}

}  // namespace
}  // namespace periflex
