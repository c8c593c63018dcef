// The plot's layout, shared by the window and recorded frames: the y axis spans every series
// shown, each series gets its own colour and points, the titles carry the units, lines stay
// inside the frame when the x range is zoomed, and the overlay's plot keeps to its box at the
// top right. No GL, no ImGui: text is measured by a fixed-width rule.
#include "render/plot_figure.h"

#include <gtest/gtest.h>

#include <memory>

#include "plot_rows.h"

#include "render/overlay_layout.h"

namespace periflex {
namespace {

using testing::two_series;

// 7 pixels a character, 13 a line
PlotTextMetrics fixed_text() {
  PlotTextMetrics m;
  m.width = [](const std::string& s) { return 7.0f * static_cast<float>(s.size()); };
  m.height = 13.0f;
  return m;
}

bool same_colour(Rgba8 a, Rgba8 b) { return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a; }

TEST(PlotFigure, AxisSpansEverySeriesAndEachHasItsPoints) {
  const PlotHistory h = two_series(11);
  PlotView view;
  view.y_columns = {"driver_work", "fracture"};
  view.x_lo = 0.0;
  view.x_hi = 1.0;
  const PlotFrame frame = layout_plot({10, 10}, {400, 300}, h, view, fixed_text()).frame;
  ASSERT_FALSE(frame.empty);
  // from -20 (fracture at the end) to 10 (driver_work at the end), each series widened by 5% of
  // its own span: [-21, 1] and [-0.5, 10.5]
  EXPECT_DOUBLE_EQ(frame.y_lo, -21.0);
  EXPECT_DOUBLE_EQ(frame.y_hi, 10.5);
  ASSERT_EQ(frame.points.size(), 2u);
  ASSERT_EQ(frame.points[0].size(), 11u);
  ASSERT_EQ(frame.points[1].size(), 11u);
  // both start at 0 (one pixel row); at the end driver_work is above, fracture below
  EXPECT_FLOAT_EQ(frame.points[0].front().y, frame.points[1].front().y);
  EXPECT_LT(frame.points[0].back().y, frame.points[0].front().y);
  EXPECT_GT(frame.points[1].back().y, frame.points[1].front().y);
  // the last points at the right edge of the frame, the lowest value at its bottom edge and a bit
  EXPECT_FLOAT_EQ(frame.points[0].back().x, frame.p1.x);
  EXPECT_NEAR(frame.points[1].back().y, frame.p1.y - 1.0 / 31.5 * (frame.p1.y - frame.p0.y), 0.01);
  // a column the history lacks is left out
  view.y_columns = {"driver_work", "no_such_column"};
  EXPECT_EQ(layout_plot({10, 10}, {400, 300}, h, view, fixed_text()).frame.points.size(), 1u);
}

TEST(PlotFigure, SeriesLinesAreClippedToTheFrameWhenZoomed) {
  const PlotHistory h = two_series(11);
  PlotView view;
  view.y_columns = {"driver_work"};
  view.x_lo = 0.25;  // between rows, so segments cross both sides of the frame
  view.x_hi = 0.65;
  view.cursor_time = 0.9;  // outside the range: no cursor
  const PlotFigure figure = layout_plot({0, 0}, {300, 200}, h, view, fixed_text());
  const PlotFrame& f = figure.frame;
  int series_lines = 0;
  for (const PlotShape& s : figure.shapes) {
    if (s.kind != PlotShape::Kind::kLine || !same_colour(s.colour, plot_colour(0)) || s.width != 1.5f) continue;
    ++series_lines;
    // one run cut where it enters and leaves (the bottom and top edges: rows 2 and 7 lie outside
    // the range of rows 3 to 6), every point inside the frame
    ASSERT_GE(s.points.size(), 2u);
    EXPECT_FLOAT_EQ(s.points.front().y, f.p1.y);
    EXPECT_FLOAT_EQ(s.points.back().y, f.p0.y);
    for (const PlotPoint& p : s.points) {
      EXPECT_GE(p.x, f.p0.x);
      EXPECT_LE(p.x, f.p1.x);
      EXPECT_GE(p.y, f.p0.y - 1e-3f);
      EXPECT_LE(p.y, f.p1.y + 1e-3f);
    }
    // rows 3 to 6 lie inside: the clipped ends plus those four
    EXPECT_EQ(s.points.size(), 6u);
  }
  EXPECT_EQ(series_lines, 1);
  // the unclipped points stay in the frame's readout (for the pointer)
  EXPECT_EQ(f.points[0].size(), 11u);
  // no cursor line: nothing drawn at the cursor's colour
  for (const PlotShape& s : figure.shapes) EXPECT_FALSE(same_colour(s.colour, Rgba8{90, 220, 255, 255}));
}

TEST(PlotFigure, LegendNamesEachSeriesInItsColourWithItsUnit) {
  const PlotHistory h = two_series(5);
  PlotView view;
  view.y_columns = {"driver_work", "probe.tip.y"};
  view.x_hi = 0.4;
  const PlotFigure figure = layout_plot({0, 0}, {300, 200}, h, view, fixed_text());
  std::vector<std::string> texts;
  for (const PlotShape& s : figure.shapes)
    if (s.kind == PlotShape::Kind::kText) texts.push_back(s.text);
  const auto has = [&](const std::string& t, Rgba8 colour) {
    for (const PlotShape& s : figure.shapes)
      if (s.kind == PlotShape::Kind::kText && s.text == t && same_colour(s.colour, colour)) return true;
    return false;
  };
  EXPECT_TRUE(has("driver_work [J]", plot_colour(0)));
  EXPECT_TRUE(has("probe.tip.y [m]", plot_colour(1)));
  EXPECT_TRUE(has("[J, m]", Rgba8{200, 200, 200, 255}));
  EXPECT_TRUE(has("t [s]", Rgba8{200, 200, 200, 255}));
}

TEST(PlotFigure, TitlesCarryTheUnits) {
  EXPECT_EQ(plot_axis_title("driver_work"), "driver_work [J]");
  EXPECT_EQ(plot_axis_title("made_up"), "made_up");
  EXPECT_EQ(plot_y_title({"kinetic"}), "kinetic [J]");
  EXPECT_EQ(plot_y_title({"driver_work", "fracture"}), "[J]");
  EXPECT_EQ(plot_y_title({"driver_work", "probe.tip.y", "fracture"}), "[J, m]");
  EXPECT_FALSE(same_colour(plot_colour(0), plot_colour(1)));
}

TEST(PlotFigure, ColumnRangeIsTheFiniteSpanWidenedWhenFlat) {
  const PlotHistory h = two_series(5);
  double lo = 0, hi = 0;
  ASSERT_TRUE(plot_column_range(h, "t", lo, hi));
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 0.4);
  ASSERT_TRUE(plot_column_range(h, "probe.tip.y", lo, hi));
  EXPECT_LT(lo, 0.0);
  EXPECT_GT(hi, 0.0);
  EXPECT_FALSE(plot_column_range(h, "no_such_column", lo, hi));
}

TEST(PlotFigure, OverlayPlotKeepsToItsBoxAtTheTopRight) {
  const PlotHistory h = two_series(11);
  PlotView view;
  view.y_columns = {"driver_work", "fracture"};
  view.x_hi = 1.0;
  for (const auto& [w, ht] : {std::pair{320, 200}, std::pair{1280, 720}, std::pair{1920, 1080}}) {
    PlotPoint origin, size;
    plot_box(0, w, ht, origin, size);
    // right of the middle, clear of the text at the top left and the legend and scale bar below
    EXPECT_GT(origin.x, 0.5f * w) << w << "x" << ht;
    EXPECT_FLOAT_EQ(origin.x + size.x, float(w - kOverlayMargin));
    EXPECT_FLOAT_EQ(origin.y, float(kOverlayMargin));
    EXPECT_LT(origin.y + size.y, 0.75f * ht);
    SolidMesh mesh;
    build_plot_overlay(mesh, h, view, 0, w, ht);
    ASSERT_FALSE(mesh.vertices().empty());
    // every triangle inside the box (line caps and text may reach a pixel or two over)
    for (const SolidVertex& v : mesh.vertices()) {
      EXPECT_GE(v.x, origin.x - 2.0f) << w << "x" << ht;
      EXPECT_LE(v.x, origin.x + size.x + 2.0f) << w << "x" << ht;
      EXPECT_GE(v.y, origin.y - 2.0f) << w << "x" << ht;
      EXPECT_LE(v.y, origin.y + size.y + 2.0f) << w << "x" << ht;
    }
  }
}

}  // namespace
}  // namespace periflex
