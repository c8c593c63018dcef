// A plot of series.csv columns laid out as shapes in pixels (x right, y down): a background,
// grid, ticks with labels, axis titles with units, one line per series, a legend and the
// cursor. The window paints the shapes with Dear ImGui (app/plot_drawing.h) and the renderer into
// recorded frames (Renderer::draw_overlay), so a movie shows the plot the window shows. No GL,
// no ImGui.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render/plot_history.h"
#include "render/solid_mesh.h"

namespace periflex {

// What a plot shows: one or more columns against one, over an x range.
struct PlotView {
  std::string x_column = "t";
  std::vector<std::string> y_columns = {"kinetic"};  // one line each, in plot_colour(i)
  double x_lo = 0.0, x_hi = 1.0;                     // the x range shown
  // The instant shown: against time a vertical line at it, against another column a ring on
  // each series' latest point. NaN: none.
  double cursor_time = 0.0;
};

struct PlotPoint {
  float x = 0.0f, y = 0.0f;
};

// Where a plot's parts went, for readouts under the pointer.
struct PlotFrame {
  PlotPoint p0, p1;  // the inner frame (top left, bottom right) in pixels
  double y_lo = -1.0, y_hi = 1.0;
  bool empty = true;  // no series had a point in the x range
  // each series' points in pixels (inside the frame or not), and their rows in the history
  std::vector<std::vector<PlotPoint>> points;
  std::vector<std::vector<size_t>> rows;
};

// One shape of a plot, in drawing order.
struct PlotShape {
  enum class Kind {
    kFill,     // a filled rectangle between points[0] and points[1]
    kOutline,  // the outline of that rectangle, `width` wide
    kLine,     // joined segments through `points`, `width` wide
    kRing,     // a circle of `radius` about points[0], `width` wide
    kText,     // `text` with its top-left corner at points[0]
  };
  Kind kind = Kind::kLine;
  std::vector<PlotPoint> points;
  Rgba8 colour;
  float width = 1.0f;
  float radius = 0.0f;
  std::string text;
};

// How the painter's font measures a line of text, in pixels.
struct PlotTextMetrics {
  std::function<float(const std::string&)> width;
  float height = 13.0f;
};

struct PlotFigure {
  std::vector<PlotShape> shapes;
  PlotFrame frame;
};

// The colour of the i-th series (orange, blue, green, ... as many as eight apart).
Rgba8 plot_colour(size_t i);

// "kinetic [J]", or the bare name when the unit is not known.
std::string plot_axis_title(const std::string& column);

// The y axis title of several series: the first's when there is one, else the units they carry
// ("[J]", "[J, m]"), the names in the legend.
std::string plot_y_title(const std::vector<std::string>& columns);

// The finite range of a column over the whole history, widened when flat. False when the
// column holds no finite value.
bool plot_column_range(const PlotHistory& history, const std::string& column, double& lo, double& hi);

// Lays the plot out in the box at `origin` of `size` pixels. Columns the history lacks are left
// out. Lines are clipped to the inner frame, so a painter needs no clipping of its own. `scale`
// multiplies the margins and line widths (1 in the window, larger for big frames).
PlotFigure layout_plot(PlotPoint origin, PlotPoint size, const PlotHistory& history, const PlotView& view,
                       const PlotTextMetrics& text, float scale = 1.0f);

}  // namespace periflex
