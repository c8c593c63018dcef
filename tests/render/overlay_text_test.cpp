// Overlay text as glyph quads: the ink stays inside the box the measuring functions give, whole
// scales magnify it exactly, and bytes outside printable ASCII cannot reach past the font's
// tables. No GL needed.
#include "render/overlay_text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace periflex {
namespace {

struct Box {
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
};

Box ink_box(const SolidMesh& mesh) {
  Box b;
  for (const SolidVertex& v : mesh.vertices()) {
    b.x0 = std::min<double>(b.x0, v.x);
    b.y0 = std::min<double>(b.y0, v.y);
    b.x1 = std::max<double>(b.x1, v.x);
    b.y1 = std::max<double>(b.y1, v.y);
  }
  return b;
}

TEST(OverlayText, InkStaysInsideTheMeasuredBoxAtEveryScale) {
  const std::string text = "t = 0.25 s   step 1200 (gjpqy)";
  for (int scale = 1; scale <= 4; ++scale) {
    SolidMesh mesh;
    append_text(mesh, 10, 20, text, scale, Rgba8{});
    ASSERT_FALSE(mesh.vertices().empty());
    EXPECT_EQ(mesh.vertices().size() % 6, 0u) << "two triangles per glyph quad";
    const Box b = ink_box(mesh);
    EXPECT_GE(b.x0, 10.0);
    EXPECT_GE(b.y0, 20.0);
    EXPECT_LE(b.x1, 10.0 + text_width_px(text, scale)) << "scale " << scale;
    EXPECT_LE(b.y1, 20.0 + text_height_px(scale)) << "scale " << scale;
    // and the box is not much larger than the ink: text measured this way lines up
    EXPECT_GT(b.x1, 10.0 + text_width_px(text, scale) - 4.0 * scale);
    EXPECT_GT(b.y1, 20.0 + text_height_px(scale) - 2.0 * scale);
  }
}

TEST(OverlayText, WholeScalesMagnifyExactly) {
  SolidMesh one, three;
  append_text(one, 0, 0, "damage [-]", 1, Rgba8{});
  append_text(three, 0, 0, "damage [-]", 3, Rgba8{});
  ASSERT_EQ(one.vertices().size(), three.vertices().size());
  for (size_t i = 0; i < one.vertices().size(); ++i) {
    EXPECT_FLOAT_EQ(three.vertices()[i].x, 3.0f * one.vertices()[i].x);
    EXPECT_FLOAT_EQ(three.vertices()[i].y, 3.0f * one.vertices()[i].y);
  }
  EXPECT_EQ(text_width_px("damage [-]", 3), 3 * text_width_px("damage [-]", 1));
}

TEST(OverlayText, GlyphsCarryTheColourAndDifferBetweenCharacters) {
  SolidMesh seven, one;
  append_text(seven, 0, 0, "7", 1, Rgba8{1, 2, 3, 4});
  append_text(one, 0, 0, "1", 1, Rgba8{1, 2, 3, 4});
  ASSERT_FALSE(seven.vertices().empty());
  EXPECT_NE(ink_box(seven).x1 - ink_box(seven).x0, ink_box(one).x1 - ink_box(one).x0);
  for (const SolidVertex& v : seven.vertices()) {
    EXPECT_EQ(v.r, 1);
    EXPECT_EQ(v.a, 4);
  }
}

TEST(OverlayText, BytesOutsidePrintableAsciiAreShownAsQuestionMarks) {
  // a scene name in UTF-8 ("é" is two bytes) and control characters
  SolidMesh utf8, marks;
  append_text(utf8, 0, 0, "pl\xc3\xa9", 1, Rgba8{});
  append_text(marks, 0, 0, "pl??", 1, Rgba8{});
  ASSERT_EQ(utf8.vertices().size(), marks.vertices().size());
  for (size_t i = 0; i < utf8.vertices().size(); ++i) EXPECT_EQ(utf8.vertices()[i].x, marks.vertices()[i].x);
  EXPECT_EQ(text_width_px("a\tb\x7f", 1), text_width_px("a?b?", 1));
}

TEST(OverlayText, SpacesDrawNothingButTakeRoom) {
  SolidMesh mesh;
  append_text(mesh, 0, 0, "   ", 2, Rgba8{});
  append_text(mesh, 0, 0, "", 2, Rgba8{});
  EXPECT_TRUE(mesh.vertices().empty());
  EXPECT_GT(text_width_px("   ", 2), 0);
}

TEST(OverlayText, ScaleGrowsWithThePicture) {
  EXPECT_EQ(overlay_text_scale(320, 240), 1);
  EXPECT_EQ(overlay_text_scale(1280, 640), 1);
  EXPECT_EQ(overlay_text_scale(1920, 1080), 2);
  EXPECT_EQ(overlay_text_scale(3840, 2160), 4);
  EXPECT_EQ(overlay_text_scale(0, 0), 1);
}

}  // namespace
}  // namespace periflex
