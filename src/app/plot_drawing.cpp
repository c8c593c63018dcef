#include "app/plot_drawing.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "output/series_row.h"
#include "render/plot_axes.h"

namespace periflex {

namespace {

// text at the current font scaled by the plot's scale
struct PlotText {
  ImFont* font;
  float size;
  ImVec2 measure(const std::string& s) const { return font->CalcTextSizeA(size, FLT_MAX, 0.0f, s.c_str()); }
  void put(ImDrawList& list, ImVec2 at, ImU32 colour, const std::string& s) const {
    list.AddText(font, size, at, colour, s.c_str());
  }
};

}  // namespace

ImU32 plot_colour(size_t i) {
  // distinct on the dark background, the first the window's single-series orange
  static const ImU32 colours[] = {IM_COL32(255, 190, 60, 255),  IM_COL32(90, 160, 255, 255),
                                  IM_COL32(120, 220, 110, 255), IM_COL32(240, 90, 200, 255),
                                  IM_COL32(255, 110, 90, 255),  IM_COL32(170, 140, 255, 255),
                                  IM_COL32(230, 230, 120, 255), IM_COL32(120, 230, 230, 255)};
  return colours[i % (sizeof colours / sizeof colours[0])];
}

std::string plot_axis_title(const std::string& column) {
  const std::string unit = series_unit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

std::string plot_y_title(const std::vector<std::string>& columns) {
  if (columns.size() == 1) return plot_axis_title(columns.front());
  // the distinct units, in the order of the series
  std::vector<std::string> units;
  for (const std::string& c : columns) {
    const std::string u = series_unit(c);
    if (!u.empty() && std::find(units.begin(), units.end(), u) == units.end()) units.push_back(u);
  }
  std::string title;
  for (const std::string& u : units) title += (title.empty() ? "[" : ", ") + u;
  return title.empty() ? title : title + "]";
}

bool plot_column_range(const PlotHistory& history, const std::string& column, double& lo, double& hi) {
  const int index = history.index_of(column);
  if (index < 0) return false;
  lo = HUGE_VAL, hi = -HUGE_VAL;
  for (double v : history.values(index)) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo > hi) return false;
  // a flat column: 5% of its value each side, or [-1, 1] about zero
  if (hi <= lo) {
    const double pad = lo != 0.0 ? 0.05 * std::fabs(lo) : 1.0;
    hi = lo + pad;
    lo -= pad;
  }
  return true;
}

PlotFrame draw_plot(ImDrawList& list, ImVec2 origin, ImVec2 size, const PlotHistory& history, const PlotView& view,
                    float scale) {
  PlotFrame frame;
  const PlotText text{ImGui::GetFont(), ImGui::GetFontSize() * scale};
  const float left = 62.0f * scale, bottom = 36.0f * scale, top = 8.0f * scale, right = 12.0f * scale;
  frame.p0 = ImVec2(origin.x + left, origin.y + top);
  frame.p1 = ImVec2(origin.x + size.x - right, origin.y + size.y - bottom);
  const ImVec2 p0 = frame.p0, p1 = frame.p1;
  const double x_lo = view.x_lo, x_hi = view.x_hi > view.x_lo ? view.x_hi : view.x_lo + 1.0;

  // the series the history holds, and the y range over their visible points
  const int ix = history.index_of(view.x_column);
  std::vector<int> shown;
  std::vector<std::string> names;
  double y_lo = HUGE_VAL, y_hi = -HUGE_VAL;
  for (const std::string& c : view.y_columns) {
    const int iy = history.index_of(c);
    if (ix < 0 || iy < 0) continue;
    shown.push_back(iy);
    names.push_back(c);
    double lo = 0.0, hi = 0.0;
    if (visible_range(history.values(ix), history.values(iy), x_lo, x_hi, lo, hi)) {
      y_lo = std::min(y_lo, lo);
      y_hi = std::max(y_hi, hi);
    }
  }
  frame.empty = !(y_hi >= y_lo);
  if (frame.empty) y_lo = -1.0, y_hi = 1.0;
  frame.y_lo = y_lo;
  frame.y_hi = y_hi;
  const auto to_x = [&](double v) { return p0.x + float((v - x_lo) / (x_hi - x_lo)) * (p1.x - p0.x); };
  const auto to_y = [&](double v) { return p1.y - float((v - y_lo) / (y_hi - y_lo)) * (p1.y - p0.y); };

  const ImU32 axis = IM_COL32(200, 200, 200, 255), grid = IM_COL32(90, 90, 90, 120);
  const ImU32 cursor = IM_COL32(90, 220, 255, 255);
  list.AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(12, 13, 16, 220));
  list.AddRectFilled(p0, p1, IM_COL32(20, 22, 26, 255));
  // ticks and grid lines with their labels
  const std::vector<double> xt = nice_ticks(x_lo, x_hi, std::max(2, int((p1.x - p0.x) / (90.0f * scale))));
  const std::vector<double> yt = nice_ticks(y_lo, y_hi, std::max(2, int((p1.y - p0.y) / (40.0f * scale))));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double v : xt) {
    const float x = to_x(v);
    list.AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), grid, scale);
    list.AddLine(ImVec2(x, p1.y), ImVec2(x, p1.y + 4.0f * scale), axis, scale);
    const std::string label = tick_label(v, xstep);
    text.put(list, ImVec2(x - 0.5f * text.measure(label).x, p1.y + 5.0f * scale), axis, label);
  }
  for (double v : yt) {
    const float y = to_y(v);
    list.AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), grid, scale);
    list.AddLine(ImVec2(p0.x - 4.0f * scale, y), ImVec2(p0.x, y), axis, scale);
    const std::string label = tick_label(v, ystep);
    const ImVec2 ts = text.measure(label);
    text.put(list, ImVec2(p0.x - 6.0f * scale - ts.x, y - 0.5f * ts.y), axis, label);
  }
  list.AddRect(p0, p1, axis, 0.0f, 0, scale);
  // the x title with its unit below the ticks
  const std::string xtitle = plot_axis_title(view.x_column);
  text.put(list, ImVec2(0.5f * (p0.x + p1.x) - 0.5f * text.measure(xtitle).x, p1.y + 19.0f * scale), axis, xtitle);

  // the series, clipped to the frame
  list.PushClipRect(p0, p1, true);
  frame.points.resize(shown.size());
  frame.rows.resize(shown.size());
  for (size_t k = 0; k < shown.size(); ++k) {
    const std::vector<double>& xs = history.values(ix);
    const std::vector<double>& ys = history.values(shown[k]);
    std::vector<ImVec2>& points = frame.points[k];
    for (size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
      if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
      points.emplace_back(to_x(xs[i]), to_y(ys[i]));
      frame.rows[k].push_back(i);
    }
    if (points.size() >= 2)
      list.AddPolyline(points.data(), static_cast<int>(points.size()), plot_colour(k), 0, 1.5f * scale);
  }
  // the instant shown: a vertical cursor against time, each series' latest point otherwise
  if (std::isfinite(view.cursor_time)) {
    if (view.x_column == "t") {
      const float x = to_x(view.cursor_time);
      list.AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), cursor, 1.5f * scale);
    } else {
      for (const std::vector<ImVec2>& points : frame.points)
        if (!points.empty()) list.AddCircle(points.back(), 5.0f * scale, cursor, 0, 2.0f * scale);
    }
  }
  list.PopClipRect();

  // the y title (units) at the top left, then the legend: each series' name and unit in its colour
  ImVec2 at(p0.x + 6.0f * scale, p0.y + 2.0f * scale);
  const std::string ytitle = plot_y_title(names);
  if (names.size() == 1) {
    text.put(list, at, plot_colour(0), ytitle);
  } else {
    if (!ytitle.empty()) {
      text.put(list, at, axis, ytitle);
      at.y += text.size + 2.0f * scale;
    }
    for (size_t k = 0; k < names.size(); ++k) {
      const std::string entry = plot_axis_title(names[k]);
      const float mid = at.y + 0.5f * text.size;
      list.AddLine(ImVec2(at.x, mid), ImVec2(at.x + 16.0f * scale, mid), plot_colour(k), 2.0f * scale);
      text.put(list, ImVec2(at.x + 20.0f * scale, at.y), plot_colour(k), entry);
      at.y += text.size + 2.0f * scale;
    }
  }
  return frame;
}

}  // namespace periflex
