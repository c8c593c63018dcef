// Combined shapes: the grid scan visits exactly the cells the inside test accepts, a plate
// minus holes as one shape is the plate with those holes, and the area bound never undercounts.
#include <gtest/gtest.h>

#include "scene/grid_scan.h"
#include "scene/scene_loader.h"
#include "scene/shape_boolean.h"
#include "scene/shape_reader.h"
#include "test_shapes.h"

namespace periflex {
namespace {

using test::box;
using test::circle;
using test::combined;

std::vector<std::pair<long, long>> scanned(const ShapeDef& shape, const GridFrame& frame) {
  std::vector<std::pair<long, long>> cells;
  scan_grid(shape, {}, frame, {}, [&](long j, long begin, long end) {
    for (long i = begin; i < end; ++i) cells.emplace_back(j, i);
  });
  return cells;
}

std::vector<std::pair<long, long>> tested(const ShapeDef& shape, const GridFrame& frame) {
  std::vector<std::pair<long, long>> cells;
  for (long j = 0; j < frame.ny; ++j)
    for (long i = 0; i < frame.nx; ++i)
      if (shape.contains(frame.cell(i, j))) cells.emplace_back(j, i);
  return cells;
}

TEST(ShapeBoolean, ScanVisitsExactlyTheCellsTheInsideTestAccepts) {
  const ShapeDef plate = box({0, 0}, 1.0, 0.6, 0.2);
  const ShapeDef disc = circle({0.1, 0.05}, 0.2);
  const ShapeDef tilted = box({-0.3, -0.2}, 0.3, 0.1, 0.7);
  const std::vector<ShapeDef> cases = {
      combined(ShapeDef::Combine::kUnion, {disc, tilted, circle({0.9, 0.9}, 0.1)}),
      combined(ShapeDef::Combine::kDifference, {plate, disc, tilted}),
      combined(ShapeDef::Combine::kIntersection, {plate, circle({0.4, 0.2}, 0.35)}),
      // nested: (plate minus disc) united with a ring made of a difference
      combined(ShapeDef::Combine::kUnion, {combined(ShapeDef::Combine::kDifference, {plate, disc}),
                                           combined(ShapeDef::Combine::kDifference,
                                                    {circle({1.0, 0}, 0.3), circle({1.0, 0}, 0.2)})})};
  for (size_t k = 0; k < cases.size(); ++k) {
    const ShapeDef& s = cases[k];
    for (double dx : {0.013, 0.05}) {
      const GridFrame frame = grid_frame(s, dx);
      const auto cells = scanned(s, frame);
      EXPECT_EQ(cells, tested(s, frame)) << "case " << k << " dx " << dx;
      EXPECT_FALSE(cells.empty());
      // the bound the budget's first look uses is not below the area filled
      EXPECT_GE(shape_area(s), 0.9 * static_cast<double>(cells.size()) * dx * dx) << k;
    }
  }
}

// The bounds cover every cell inside, so a combined body's grid frame loses none.
TEST(ShapeBoolean, BoundsCoverTheShape) {
  const ShapeDef u = combined(ShapeDef::Combine::kUnion, {circle({-1, 0}, 0.5), circle({2, 1}, 0.25)});
  Vec2 lo, hi;
  shape_bounds(u, lo, hi);
  EXPECT_EQ(lo, Vec2(-1.5, -0.5));
  EXPECT_EQ(hi, Vec2(2.25, 1.25));
  const ShapeDef i = combined(ShapeDef::Combine::kIntersection, {box({0, 0}, 2, 2), box({1, 1}, 2, 2)});
  shape_bounds(i, lo, hi);
  EXPECT_EQ(lo, Vec2(0, 0));
  EXPECT_EQ(hi, Vec2(1, 1));
}

const char* kScene = R"(
[solver]
integrator = "verlet"
dt = 1e-7
end_time = 1e-6
[[flex_body]]
name = "plate"
SHAPE
grid_spacing = 1e-3
[flex_body.material]
youngs_modulus = 3.2e9
density = 1190.0
critical_stretch = 0.01
)";

SceneDef scene_with(const std::string& shape) {
  std::string text = kScene;
  text.replace(text.find("SHAPE"), 5, shape);
  return parse_scene(text, "combined.toml");
}

// The plate with a hole typed as holes, and as one difference: the same particles.
TEST(ShapeBoolean, DifferenceIsTheShapeWithHoles) {
  const SceneDef holes = scene_with(
      "shape = { type = \"box\", width = 0.08, height = 0.04 }\n"
      "holes = [ { type = \"circle\", radius = 0.006 }, { type = \"box\", center = [-0.03, 0], width = 0.02, height = 0.002 } ]");
  const SceneDef one = scene_with(
      "shape = { type = \"difference\", shapes = [ { type = \"box\", width = 0.08, height = 0.04 },"
      " { type = \"circle\", radius = 0.006 }, { type = \"box\", center = [-0.03, 0], width = 0.02, height = 0.002 } ] }");
  const FlexBodyDef& a = holes.flex_bodies[0];
  const FlexBodyDef& b = one.flex_bodies[0];
  const GridFrame fa = grid_frame(a.shape, a.grid_spacing), fb = grid_frame(b.shape, b.grid_spacing);
  std::vector<Vec2> pa, pb;
  scan_grid(a.shape, a.holes, fa, {}, [&](long j, long begin, long end) {
    for (long i = begin; i < end; ++i) pa.push_back(fa.cell(i, j));
  });
  scan_grid(b.shape, b.holes, fb, {}, [&](long j, long begin, long end) {
    for (long i = begin; i < end; ++i) pb.push_back(fb.cell(i, j));
  });
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(pa.size(), 3200u - 112u - 40u);  // 80 x 40 cells, the disc's 112 and the slot's 20 x 2
  for (size_t k = 0; k < pa.size(); ++k) EXPECT_EQ(pa[k], pb[k]);
}

TEST(ShapeBoolean, TooFewOperandsAndRigidBodiesRefused) {
  EXPECT_THROW(scene_with("shape = { type = \"difference\", shapes = [ { type = \"box\", width = 1, height = 1 } ] }"),
               InputError);
  EXPECT_THROW(scene_with("shape = { type = \"union\" }"), InputError);
}

}  // namespace
}  // namespace periflex
