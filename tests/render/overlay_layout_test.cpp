// Where the overlay's parts go: the text box at the top left of the picture (beside a panel
// column when asked), the legend's columns in colour-map order, a scale bar of a round length.
// No GL needed.
#include "render/overlay_layout.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "render/overlay_text.h"

namespace periflex {
namespace {

constexpr int kWidth = 640, kHeight = 480;

// a colour map whose entry i is (i, 255 - i, 7)
std::vector<unsigned char> ramp() {
  std::vector<unsigned char> table(256 * 4);
  for (int i = 0; i < 256; ++i) {
    table[4 * i] = static_cast<unsigned char>(i);
    table[4 * i + 1] = static_cast<unsigned char>(255 - i);
    table[4 * i + 2] = 7;
    table[4 * i + 3] = 255;
  }
  return table;
}

float min_x(const SolidMesh& m) {
  float x = 1e9f;
  for (const auto& v : m.vertices()) x = std::min(x, v.x);
  return x;
}

TEST(OverlayLayout, TextBoxSitsAtTheTopLeftAndHoldsEveryLine) {
  OverlayContent content;
  content.lines = {"flexible pendulum", "t = 0.5 s   step 500"};
  SolidMesh mesh;
  build_overlay(mesh, content, 0, kWidth, kHeight);
  ASSERT_FALSE(mesh.vertices().empty());
  // the shaded box is the first rectangle: from the margin to past the widest line
  const SolidVertex& corner = mesh.vertices()[0];
  EXPECT_EQ(corner.x, kOverlayMargin);
  EXPECT_EQ(corner.y, kOverlayMargin);
  float right = 0, bottom = 0;
  for (size_t i = 0; i < 6; ++i) {
    right = std::max(right, mesh.vertices()[i].x);
    bottom = std::max(bottom, mesh.vertices()[i].y);
  }
  EXPECT_GE(right, kOverlayMargin + text_width_px(content.lines[0], 1));
  EXPECT_GE(bottom, kOverlayMargin + 2 * text_height_px(1));
  // every glyph lies inside it
  for (const auto& v : mesh.vertices()) {
    EXPECT_LE(v.x, right);
    EXPECT_LE(v.y, bottom);
  }
}

TEST(OverlayLayout, LeftColumnMovesEverythingRight) {
  OverlayContent content;
  content.lines = {"four bar"};
  content.pixel_world = 1e-3;
  content.legend = true;
  const auto table = ramp();
  content.colormap = &table;
  SolidMesh plain, beside;
  build_overlay(plain, content, 0, kWidth, kHeight);
  build_overlay(beside, content, 300, kWidth + 300, kHeight);
  ASSERT_EQ(plain.vertices().size(), beside.vertices().size());
  for (size_t i = 0; i < plain.vertices().size(); ++i) {
    EXPECT_FLOAT_EQ(beside.vertices()[i].x, plain.vertices()[i].x + 300.0f);
    EXPECT_FLOAT_EQ(beside.vertices()[i].y, plain.vertices()[i].y);
  }
  EXPECT_GE(min_x(beside), 300.0f);
}

TEST(OverlayLayout, LegendColumnsFollowTheColourMapFromFirstToLastEntry) {
  OverlayContent content;
  content.legend = true;
  content.legend_title = "damage [-]";
  const auto table = ramp();
  content.colormap = &table;
  SolidMesh mesh;
  build_overlay(mesh, content, 0, kWidth, kHeight);
  // columns are the triangles with blue 7; their red rises left to right from 0 to 255
  std::vector<std::pair<float, int>> columns;
  for (const auto& v : mesh.vertices())
    if (v.b == 7) columns.emplace_back(v.x, v.r);
  ASSERT_GE(columns.size(), 6u * kLegendBarMaxWidth);
  std::sort(columns.begin(), columns.end());
  EXPECT_EQ(columns.front().second, 0);
  EXPECT_EQ(columns.back().second, 255);
  for (size_t i = 1; i < columns.size(); ++i) EXPECT_GE(columns[i].second, columns[i - 1].second);
  // the bar sits above the bottom edge, clear of it
  for (const auto& v : mesh.vertices()) EXPECT_LE(v.y, kHeight - kOverlayMargin);
}

TEST(OverlayLayout, NoLegendWithoutParticlesAndNoBarWithoutAScale) {
  OverlayContent content;
  const auto table = ramp();
  content.colormap = &table;
  SolidMesh mesh;
  build_overlay(mesh, content, 0, kWidth, kHeight);
  EXPECT_TRUE(mesh.vertices().empty());
  content.pixel_world = std::numeric_limits<double>::infinity();
  build_overlay(mesh, content, 0, kWidth, kHeight);
  EXPECT_TRUE(mesh.vertices().empty());
}

TEST(OverlayLayout, ScaleBarIsARoundLengthEndingAtTheRightMargin) {
  OverlayContent content;
  content.pixel_world = 1.7e-4;  // 100 px = 17 mm: the bar shows 10 mm, 58.8 -> 59 px
  SolidMesh mesh;
  build_overlay(mesh, content, 0, kWidth, kHeight);
  // the bar's line is the second rectangle (after its shaded box)
  float x0 = 1e9f, x1 = -1e9f;
  for (size_t i = 6; i < 12; ++i) {
    x0 = std::min(x0, mesh.vertices()[i].x);
    x1 = std::max(x1, mesh.vertices()[i].x);
  }
  EXPECT_FLOAT_EQ(x1, kWidth - 14.0f);
  EXPECT_FLOAT_EQ(x1 - x0, 59.0f);
}

TEST(OverlayLayout, LengthsInTheUnitThatReadsBest) {
  EXPECT_EQ(format_length(2.0), "2 m");
  EXPECT_EQ(format_length(0.01), "10 mm");
  EXPECT_EQ(format_length(5e-4), "500 um");
}

}  // namespace
}  // namespace periflex
