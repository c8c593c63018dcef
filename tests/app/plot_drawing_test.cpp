// The window's plot: the shared layout (render/plot_figure.h, tested there) painted into a Dear
// ImGui draw list of a context without any GL back end (the draw list is only built, never
// rendered).
#include "app/plot_drawing.h"

#include <gtest/gtest.h>

#include <memory>

#include "../render/plot_rows.h"

namespace periflex {
namespace {

using testing::two_series;

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

TEST(PlotDrawing, PaintsTheLayoutInTheWindowsFont) {
  DrawContext ui;
  const PlotHistory h = two_series(11);
  PlotView view;
  view.y_columns = {"driver_work", "fracture"};
  view.x_hi = 1.0;
  ImDrawList& list = *ImGui::GetForegroundDrawList();
  const int before = list.VtxBuffer.Size;
  const PlotFrame frame = draw_plot(list, ImVec2(10, 10), ImVec2(400, 300), h, view);
  // the shapes went into the draw list, and the frame is the layout's with the font's metrics
  EXPECT_GT(list.VtxBuffer.Size, before + 200);
  PlotTextMetrics metrics;
  metrics.width = [](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x; };
  metrics.height = ImGui::GetFontSize();
  const PlotFrame laid = layout_plot({10, 10}, {400, 300}, h, view, metrics).frame;
  EXPECT_FLOAT_EQ(frame.p0.x, laid.p0.x);
  EXPECT_FLOAT_EQ(frame.p1.y, laid.p1.y);
  ASSERT_EQ(frame.points.size(), 2u);
  EXPECT_FLOAT_EQ(frame.points[1].back().y, laid.points[1].back().y);
  EXPECT_EQ(imgui_colour(plot_colour(1)), IM_COL32(90, 160, 255, 255));
}

}  // namespace
}  // namespace periflex
