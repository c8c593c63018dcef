#include "render/plot_figure.h"

#include <algorithm>
#include <cmath>

#include "output/series_row.h"
#include "render/plot_axes.h"

namespace periflex {

namespace {

constexpr Rgba8 kAxis{200, 200, 200, 255}, kGrid{90, 90, 90, 120}, kCursor{90, 220, 255, 255};
constexpr Rgba8 kBox{12, 13, 16, 220}, kInside{20, 22, 26, 255};

// Appends shapes in drawing order.
struct ShapeList {
  std::vector<PlotShape>& shapes;

  void rect(PlotShape::Kind kind, PlotPoint a, PlotPoint b, Rgba8 colour, float width = 1.0f) {
    shapes.push_back({kind, {a, b}, colour, width, 0.0f, {}});
  }
  void line(std::vector<PlotPoint> points, Rgba8 colour, float width) {
    if (points.size() >= 2) shapes.push_back({PlotShape::Kind::kLine, std::move(points), colour, width, 0.0f, {}});
  }
  void ring(PlotPoint centre, float radius, Rgba8 colour, float width) {
    shapes.push_back({PlotShape::Kind::kRing, {centre}, colour, width, radius, {}});
  }
  void text(PlotPoint at, Rgba8 colour, const std::string& s) {
    shapes.push_back({PlotShape::Kind::kText, {at}, colour, 1.0f, 0.0f, s});
  }
};

// The part of segment a-b inside the box [p0, p1] (Liang-Barsky); false when none is.
bool clip_segment(PlotPoint p0, PlotPoint p1, PlotPoint& a, PlotPoint& b) {
  const float dx = b.x - a.x, dy = b.y - a.y;
  float t0 = 0.0f, t1 = 1.0f;
  const float p[4] = {-dx, dx, -dy, dy};
  const float q[4] = {a.x - p0.x, p1.x - a.x, a.y - p0.y, p1.y - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0f) {
      if (q[k] < 0.0f) return false;  // parallel to this edge and outside it
      continue;
    }
    const float t = q[k] / p[k];
    if (p[k] < 0.0f) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t0 > t1) return false;
  const PlotPoint from{a.x + t0 * dx, a.y + t0 * dy}, to{a.x + t1 * dx, a.y + t1 * dy};
  a = from;
  b = to;
  return true;
}

// The polyline through `points` cut to the box: one line per run of segments that stays inside.
void clipped_polyline(ShapeList& out, const std::vector<PlotPoint>& points, PlotPoint p0, PlotPoint p1, Rgba8 colour,
                      float width) {
  std::vector<PlotPoint> run;
  for (size_t i = 1; i < points.size(); ++i) {
    PlotPoint a = points[i - 1], b = points[i];
    if (!clip_segment(p0, p1, a, b)) continue;
    const bool joins = !run.empty() && run.back().x == a.x && run.back().y == a.y;
    if (!joins) {
      out.line(std::move(run), colour, width);
      run = {a};
    }
    run.push_back(b);
  }
  out.line(std::move(run), colour, width);
}

// The text cut to `room` pixels, ".." marking the cut, so a small plot's titles stay in it.
std::string fitted(const std::string& s, float room, const PlotTextMetrics& text) {
  if (text.width(s) <= room) return s;
  std::string cut = s;
  while (!cut.empty() && text.width(cut + "..") > room) cut.pop_back();
  return cut.empty() ? std::string() : cut + "..";
}

}  // namespace

Rgba8 plot_colour(size_t i) {
  // distinct on the dark background, the first the window's single-series orange
  static const Rgba8 colours[] = {{255, 190, 60, 255},  {90, 160, 255, 255}, {120, 220, 110, 255},
                                  {240, 90, 200, 255},  {255, 110, 90, 255}, {170, 140, 255, 255},
                                  {230, 230, 120, 255}, {120, 230, 230, 255}};
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

PlotFigure layout_plot(PlotPoint origin, PlotPoint size, const PlotHistory& history, const PlotView& view,
                       const PlotTextMetrics& text, float scale) {
  PlotFigure figure;
  PlotFrame& frame = figure.frame;
  ShapeList out{figure.shapes};
  // margins: tick labels and the x title below, tick labels at the left
  const float left = std::max(62.0f * scale, text.width("-0.0000") + 12.0f * scale);
  const float bottom = 2.0f * text.height + 10.0f * scale, top = 8.0f * scale, right = 12.0f * scale;
  frame.p0 = {origin.x + left, origin.y + top};
  frame.p1 = {origin.x + size.x - right, origin.y + size.y - bottom};
  const PlotPoint p0 = frame.p0, p1 = frame.p1;
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

  out.rect(PlotShape::Kind::kFill, origin, {origin.x + size.x, origin.y + size.y}, kBox);
  out.rect(PlotShape::Kind::kFill, p0, p1, kInside);
  // ticks and grid lines with their labels
  // as many as fit with room for their labels: a label's width apart along x, three lines along y
  const float x_gap = std::max(text.width("-0.0000") + 24.0f * scale, 60.0f * scale);
  const float y_gap = std::max(3.0f * text.height, 30.0f * scale);
  const std::vector<double> xt = nice_ticks(x_lo, x_hi, std::max(3, int((p1.x - p0.x) / x_gap)));
  const std::vector<double> yt = nice_ticks(y_lo, y_hi, std::max(3, int((p1.y - p0.y) / y_gap)));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double v : xt) {
    const float x = to_x(v);
    out.line({{x, p0.y}, {x, p1.y}}, kGrid, scale);
    out.line({{x, p1.y}, {x, p1.y + 4.0f * scale}}, kAxis, scale);
    // centred under its tick, the last one kept inside the box
    const std::string label = tick_label(v, xstep);
    const float w = text.width(label);
    out.text({std::min(x - 0.5f * w, origin.x + size.x - w - 2.0f * scale), p1.y + 5.0f * scale}, kAxis, label);
  }
  for (double v : yt) {
    const float y = to_y(v);
    out.line({{p0.x, y}, {p1.x, y}}, kGrid, scale);
    out.line({{p0.x - 4.0f * scale, y}, {p0.x, y}}, kAxis, scale);
    const std::string label = tick_label(v, ystep);
    out.text({p0.x - 6.0f * scale - text.width(label), y - 0.5f * text.height}, kAxis, label);
  }
  out.rect(PlotShape::Kind::kOutline, p0, p1, kAxis, scale);
  // the x title with its unit below the ticks
  const std::string xtitle = fitted(plot_axis_title(view.x_column), p1.x - p0.x, text);
  out.text({0.5f * (p0.x + p1.x) - 0.5f * text.width(xtitle), p1.y + text.height + 6.0f * scale}, kAxis, xtitle);

  // the series, clipped to the frame
  frame.points.resize(shown.size());
  frame.rows.resize(shown.size());
  for (size_t k = 0; k < shown.size(); ++k) {
    const std::vector<double>& xs = history.values(ix);
    const std::vector<double>& ys = history.values(shown[k]);
    std::vector<PlotPoint>& points = frame.points[k];
    for (size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
      if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
      points.push_back({to_x(xs[i]), to_y(ys[i])});
      frame.rows[k].push_back(i);
    }
    clipped_polyline(out, points, p0, p1, plot_colour(k), 1.5f * scale);
  }
  // the instant shown: a vertical cursor against time, each series' latest point otherwise
  const auto inside = [&](PlotPoint p) { return p.x >= p0.x && p.x <= p1.x && p.y >= p0.y && p.y <= p1.y; };
  if (std::isfinite(view.cursor_time)) {
    if (view.x_column == "t") {
      const float x = to_x(view.cursor_time);
      if (x >= p0.x && x <= p1.x) out.line({{x, p0.y}, {x, p1.y}}, kCursor, 1.5f * scale);
    } else {
      for (const std::vector<PlotPoint>& points : frame.points)
        if (!points.empty() && inside(points.back())) out.ring(points.back(), 5.0f * scale, kCursor, 2.0f * scale);
    }
  }

  // the y title (units) at the top left, then the legend: each series' name and unit in its colour
  PlotPoint at{p0.x + 6.0f * scale, p0.y + 2.0f * scale};
  const float room = p1.x - at.x - 2.0f * scale;
  const std::string ytitle = fitted(plot_y_title(names), room, text);
  if (names.size() == 1) {
    out.text(at, plot_colour(0), ytitle);
  } else {
    if (!ytitle.empty()) {
      out.text(at, kAxis, ytitle);
      at.y += text.height + 2.0f * scale;
    }
    for (size_t k = 0; k < names.size(); ++k) {
      const float mid = at.y + 0.5f * text.height;
      out.line({{at.x, mid}, {at.x + 16.0f * scale, mid}}, plot_colour(k), 2.0f * scale);
      out.text({at.x + 20.0f * scale, at.y}, plot_colour(k), fitted(plot_axis_title(names[k]), room - 20.0f * scale, text));
      at.y += text.height + 2.0f * scale;
    }
  }
  return figure;
}

}  // namespace periflex
