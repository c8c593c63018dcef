// A plot of series.csv columns drawn with Dear ImGui's draw lists, for the window's plot panel:
// axes, ticks, units, a legend and one line per series.
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

#include "render/plot_history.h"

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

// Where the last draw_plot put things, for readouts under the pointer.
struct PlotFrame {
  ImVec2 p0, p1;  // the inner frame (top left, bottom right) in screen pixels
  double y_lo = -1.0, y_hi = 1.0;
  bool empty = true;  // no series had a point in the x range
  // each series' points in screen pixels, and their rows in the history
  std::vector<std::vector<ImVec2>> points;
  std::vector<std::vector<size_t>> rows;
};

// The colour of the i-th series (orange, blue, green, ... as many as eight apart).
ImU32 plot_colour(size_t i);

// "kinetic [J]", or the bare name when the unit is not known.
std::string plot_axis_title(const std::string& column);

// The y axis title of several series: the first's when there is one, else the units they carry
// ("[J]", "[J, m]"), the names in the legend.
std::string plot_y_title(const std::vector<std::string>& columns);

// The finite range of a column over the whole history, widened when flat. False when the
// column holds no finite value.
bool plot_column_range(const PlotHistory& history, const std::string& column, double& lo, double& hi);

// Draws the plot into the box at `origin` of `size` pixels: a dark background, grid, ticks with
// labels, axis titles with units, the series, a legend naming each (with its unit) in its colour,
// and the cursor. Columns the history lacks are left out. `scale` multiplies the margins and
// line widths (1 in the window, larger for big frames); the text uses the current ImGui font.
PlotFrame draw_plot(ImDrawList& list, ImVec2 origin, ImVec2 size, const PlotHistory& history, const PlotView& view,
                    float scale = 1.0f);

}  // namespace periflex
