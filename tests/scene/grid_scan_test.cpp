// The grid scan visits exactly the cells ShapeDef::contains accepts (so the particle budget counts
// what the filler will place), and its work follows the rows and the shape's own cells, never the
// bounding box.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "scene/grid_scan.h"
#include "test_shapes.h"

namespace periflex {
namespace {

using test::box;
using test::circle;

ShapeDef polygon(std::vector<Vec2> v) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kPolygon;
  s.vertices = std::move(v);
  return s;
}

ShapeDef bar(Vec2 a, Vec2 b, double r) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBar;
  s.p1 = a;
  s.p2 = b;
  s.radius = r;
  return s;
}

// Every cell of the frame tested one by one: the definition the scan must reproduce.
std::vector<std::pair<long, long>> brute_force(const ShapeDef& shape, const std::vector<ShapeDef>& holes,
                                               const GridFrame& frame, const std::vector<ShapeDef>& inside) {
  std::vector<std::pair<long, long>> cells;
  for (long j = 0; j < frame.ny; ++j)
    for (long i = 0; i < frame.nx; ++i) {
      const Vec2 p = frame.cell(i, j);
      bool in = shape.contains(p);
      for (const ShapeDef& h : holes) in = in && !h.contains(p);
      for (const ShapeDef& s : inside) in = in && s.contains(p);
      if (in) cells.emplace_back(j, i);
    }
  return cells;
}

std::vector<std::pair<long, long>> scanned(const ShapeDef& shape, const std::vector<ShapeDef>& holes,
                                           const GridFrame& frame, const std::vector<ShapeDef>& inside) {
  std::vector<std::pair<long, long>> cells;
  scan_grid(shape, holes, frame, inside, [&](long j, long begin, long end) {
    for (long i = begin; i < end; ++i) cells.emplace_back(j, i);
  });
  return cells;
}

TEST(GridScan, VisitsExactlyTheCellsTheInsideTestAccepts) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto point = [&] { return Vec2(u(random), u(random)); };
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const double dx = 0.02 + 0.05 * std::abs(u(random));
    // the body: a rotated box, a circle, or a polygon (often self-intersecting)
    ShapeDef body;
    switch (trial % 3) {
      case 0: body = box(point(), 0.1 + std::abs(u(random)), 0.01 + std::abs(u(random)), 3.2 * u(random)); break;
      case 1: body = circle(point(), 0.05 + std::abs(u(random))); break;
      default: {
        std::vector<Vec2> v;
        for (int k = 0; k < 3 + trial % 9; ++k) v.push_back(point());
        body = polygon(v);
      }
    }
    // holes and regions of every kind
    std::vector<ShapeDef> holes = {circle(point(), 0.2 * std::abs(u(random))), bar(point(), point(), 0.05),
                                   box(point(), 0.3, 0.2, u(random))};
    std::vector<ShapeDef> inside;
    if (trial % 2 == 0) inside.push_back(polygon({point(), point(), point(), point()}));
    if (trial % 5 == 0) inside.push_back(bar(point(), point(), 0.3));
    const GridFrame frame = grid_frame(body, dx);
    EXPECT_EQ(scanned(body, holes, frame, inside), brute_force(body, holes, frame, inside));
    EXPECT_EQ(scanned(body, {}, frame, {}), brute_force(body, {}, frame, {}));
  }
}

// Grid-aligned boxes: the scan keeps the filler's placement (n dx wide holds n columns).
TEST(GridScan, AlignedBoxOfNCellsHoldsNColumns) {
  const GridFrame frame = grid_frame(box(Vec2(0.3, -0.1), 0.1, 0.04), 1e-3);
  EXPECT_EQ(count_grid_cells(box(Vec2(0.3, -0.1), 0.1, 0.04), {}, frame), 100 * 40);
}

// A 1000 m x 1 mm box at 45 degrees: 5e11 cells in its bounding box, about 1e6 inside. The
// scan works along the 7e5 rows and the particles only.
TEST(GridScan, RotatedThinBoxCostsRowsNotBoundingBoxCells) {
  const ShapeDef thin = box(Vec2::Zero(), 1000.0, 1e-3, kPi / 4);
  const GridFrame frame = grid_frame(thin, 1e-3);
  EXPECT_GT(static_cast<double>(frame.nx) * static_cast<double>(frame.ny), 4e11);
  EXPECT_LT(grid_scan_work(thin, {}, frame), 1e6);
  const auto start = std::chrono::steady_clock::now();
  const long n = count_grid_cells(thin, {}, frame);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NEAR(static_cast<double>(n), 1e6, 0.5e6);
  EXPECT_LT(seconds, 5.0);
}

// A polygon of 200 000 vertices (a fine circle): the scan pays for edges once per row they
// span, not once per cell.
TEST(GridScan, PolygonOfTwoHundredThousandVerticesIsCountedQuickly) {
  std::vector<Vec2> v;
  const int n = 200000;
  for (int k = 0; k < n; ++k) v.emplace_back(0.1 * std::cos(2 * kPi * k / n), 0.1 * std::sin(2 * kPi * k / n));
  const ShapeDef fine = polygon(v);
  const GridFrame frame = grid_frame(fine, 1e-4);
  EXPECT_LT(grid_scan_work(fine, {}, frame), 1e6);
  const long count = count_grid_cells(fine, {}, frame);
  EXPECT_NEAR(static_cast<double>(count), kPi * 0.01 / 1e-8, 0.01 * kPi * 0.01 / 1e-8);
}

// A bow-tie's shoelace area nearly cancels; the even-odd fill does not. The count is the fill's.
TEST(GridScan, BowTieIsCountedAsFilledNotByItsSignedArea) {
  const ShapeDef bow = polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1.0001}});
  const GridFrame frame = grid_frame(bow, 1e-2);
  EXPECT_EQ(count_grid_cells(bow, {}, frame), static_cast<long>(brute_force(bow, {}, frame, {}).size()));
  EXPECT_GT(count_grid_cells(bow, {}, frame), 4000);
}

}  // namespace
}  // namespace periflex
