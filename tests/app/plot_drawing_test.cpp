// The plot drawn by the window and into frames: the y axis spans every series shown, each series
// gets its own colour and points, the titles carry the units. Drawn into a Dear ImGui draw list
// of a context without any GL back end (the draw list is only built, never rendered).
#include "app/plot_drawing.h"

#include <gtest/gtest.h>

#include <memory>

namespace periflex {
namespace {

// a history of n rows: t = k / 10, driver_work = k, fracture = -2 k (made-up values)
PlotHistory two_series(int n) {
  auto columns = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"t", "driver_work", "fracture", "probe.tip.y"});
  PlotHistory h(100);
  for (int k = 0; k < n; ++k) {
    Snapshot s;
    s.step = k;
    s.time = 0.1 * k;
    s.series_columns = columns;
    s.series = {s.time, double(k), -2.0 * k, 0.0};
    h.add(s, 0.0);
  }
  return h;
}

// an ImGui context able to build draw lists: a display size and the default font's atlas
struct DrawContext {
  DrawContext() {
    context = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800, 600);
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ImGui::NewFrame();
  }
  ~DrawContext() {
    ImGui::EndFrame();
    ImGui::DestroyContext(context);
  }
  ImGuiContext* context;
};

TEST(PlotDrawing, AxisSpansEverySeriesAndEachHasItsPoints) {
  DrawContext ui;
  const PlotHistory h = two_series(11);
  PlotView view;
  view.y_columns = {"driver_work", "fracture"};
  view.x_lo = 0.0;
  view.x_hi = 1.0;
  const PlotFrame frame = draw_plot(*ImGui::GetForegroundDrawList(), ImVec2(10, 10), ImVec2(400, 300), h, view);
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
  EXPECT_EQ(draw_plot(*ImGui::GetForegroundDrawList(), ImVec2(10, 10), ImVec2(400, 300), h, view).points.size(), 1u);
}

TEST(PlotDrawing, TitlesCarryTheUnits) {
  EXPECT_EQ(plot_axis_title("driver_work"), "driver_work [J]");
  EXPECT_EQ(plot_axis_title("made_up"), "made_up");
  EXPECT_EQ(plot_y_title({"kinetic"}), "kinetic [J]");
  EXPECT_EQ(plot_y_title({"driver_work", "fracture"}), "[J]");
  EXPECT_EQ(plot_y_title({"driver_work", "probe.tip.y", "fracture"}), "[J, m]");
  EXPECT_NE(plot_colour(0), plot_colour(1));
}

TEST(PlotDrawing, ColumnRangeIsTheFiniteSpanWidenedWhenFlat) {
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

}  // namespace
}  // namespace periflex
