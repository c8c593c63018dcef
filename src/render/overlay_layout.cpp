#include "render/overlay_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/deformation.h"
#include "render/overlay_text.h"

namespace periflex {

namespace {

constexpr Rgba8 kText{240, 240, 240, 255}, kShade{0, 0, 0, 140};

// An axis-aligned rectangle from (x0, y0) to (x1, y1): whole pixels stay sharp.
void rect(SolidMesh& mesh, double x0, double y0, double x1, double y1, Rgba8 color) {
  mesh.triangle(Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), color);
  mesh.triangle(Vec2(x0, y0), Vec2(x1, y1), Vec2(x0, y1), color);
}

// The plot's shapes as triangles; text in the overlay's font at `scale`.
void append_plot_shapes(SolidMesh& mesh, const PlotFigure& figure, int scale) {
  for (const PlotShape& s : figure.shapes) {
    const auto at = [&](size_t k) { return Vec2(s.points[k].x, s.points[k].y); };
    switch (s.kind) {
      case PlotShape::Kind::kFill: rect(mesh, s.points[0].x, s.points[0].y, s.points[1].x, s.points[1].y, s.colour); break;
      case PlotShape::Kind::kOutline: {
        const Vec2 a = at(0), b = at(1);
        mesh.polyline({a, Vec2(b.x(), a.y()), b, Vec2(a.x(), b.y())}, true, s.width, s.colour);
        break;
      }
      case PlotShape::Kind::kLine: {
        std::vector<Vec2> points;
        for (size_t k = 0; k < s.points.size(); ++k) points.push_back(at(k));
        mesh.polyline(points, false, s.width, s.colour);
        break;
      }
      case PlotShape::Kind::kRing: mesh.ring_px(at(0), s.radius, s.width, s.colour); break;
      case PlotShape::Kind::kText:
        append_text(mesh, std::round(s.points[0].x), std::round(s.points[0].y), s.text, scale, s.colour);
        break;
    }
  }
}

}  // namespace

void plot_box(int left, int width, int height, PlotPoint& origin, PlotPoint& size) {
  const int w = std::max(0, width - left);
  size = {std::round(std::clamp(0.42f * w, 150.0f, 900.0f)), std::round(std::clamp(0.4f * height, 110.0f, 600.0f))};
  origin = {width - kOverlayMargin - size.x, static_cast<float>(kOverlayMargin)};
}

void build_plot_overlay(SolidMesh& mesh, const PlotHistory& history, const PlotView& view, int left, int width,
                        int height) {
  const int scale = overlay_text_scale(width - left, height);
  PlotTextMetrics metrics;
  metrics.width = [scale](const std::string& s) { return static_cast<float>(text_width_px(s, scale)); };
  metrics.height = static_cast<float>(text_height_px(scale));
  PlotPoint origin, size;
  plot_box(left, width, height, origin, size);
  append_plot_shapes(mesh, layout_plot(origin, size, history, view, metrics, static_cast<float>(scale)), scale);
}

std::string format_length(double metres) {
  char text[32];
  if (metres >= 1.0) std::snprintf(text, sizeof text, "%g m", metres);
  else if (metres >= 1e-3) std::snprintf(text, sizeof text, "%g mm", metres * 1e3);
  else std::snprintf(text, sizeof text, "%g um", metres * 1e6);
  return text;
}

void build_overlay(SolidMesh& mesh, const OverlayContent& content, int left, int width, int height) {
  const int scale = overlay_text_scale(width - left, height);
  const int text_h = text_height_px(scale);
  const int step = text_h + kOverlayLineGap;

  // top left: the lines of text on a shaded box
  if (!content.lines.empty()) {
    int text_w = 0;
    for (const std::string& l : content.lines) text_w = std::max(text_w, text_width_px(l, scale));
    const int x0 = left + kOverlayMargin, y0 = kOverlayMargin;
    const int lines = static_cast<int>(content.lines.size());
    rect(mesh, x0, y0, x0 + 2 * kOverlayPad + text_w, y0 + 2 * kOverlayPad + lines * step - kOverlayLineGap, kShade);
    for (int i = 0; i < lines; ++i)
      append_text(mesh, x0 + kOverlayPad, y0 + kOverlayPad + i * step, content.lines[i], scale, kText);
  }

  // bottom right: a scale bar of a round length (1, 2 or 5 times a power of ten), 40 to 100
  // pixels long, clear of the colour legend down to 320-pixel-wide pictures
  if (content.pixel_world > 0.0 && std::isfinite(content.pixel_world)) {
    const double metres = round_down_125(100.0 * content.pixel_world);
    const double bar = std::round(metres / content.pixel_world);
    const std::string label = format_length(metres);
    const int label_w = text_width_px(label, scale);
    const double x1 = width - 14.0, x0 = x1 - bar, yb = height - 14.0;
    const double box_half = 0.5 * std::max(bar + 12.0, label_w + 2.0 * kOverlayPad);
    const double mid = 0.5 * (x0 + x1);
    rect(mesh, std::min(x0 - 6.0, mid - box_half), yb - text_h - 10, std::max(x1 + 6.0, mid + box_half),
         height - kOverlayMargin, kShade);
    rect(mesh, x0, yb - 1, x1, yb + 1, kText);
    rect(mesh, x0 - 1, yb - 5, x0 + 1, yb + 1, kText);
    rect(mesh, x1 - 1, yb - 5, x1 + 1, yb + 1, kText);
    append_text(mesh, std::round(mid - 0.5 * label_w), yb - text_h - 6, label, scale, kText);
  }

  // bottom left: the colour legend of the particle field, a column of pixels per colour
  if (!content.legend || !content.colormap || content.colormap->size() < 256 * 4) return;
  const std::vector<unsigned char>& table = *content.colormap;
  const int bar_w = std::max(2, std::min(kLegendBarMaxWidth, (width - left) / 2));
  const int x0 = left + 12, y0 = height - 12 - text_h - 4 - kLegendBarHeight;
  rect(mesh, x0 - 6, y0 - text_h - 8, x0 + bar_w + 6, height - kOverlayMargin, kShade);
  for (int i = 0; i < bar_w; ++i) {
    const int e = 4 * (i * 255 / (bar_w - 1));
    rect(mesh, x0 + i, y0, x0 + i + 1, y0 + kLegendBarHeight, Rgba8{table[e], table[e + 1], table[e + 2], 255});
  }
  // a one-pixel frame around the bar
  rect(mesh, x0 - 1, y0 - 1, x0 + bar_w + 1, y0, kText);
  rect(mesh, x0 - 1, y0 + kLegendBarHeight, x0 + bar_w + 1, y0 + kLegendBarHeight + 1, kText);
  rect(mesh, x0 - 1, y0, x0, y0 + kLegendBarHeight, kText);
  rect(mesh, x0 + bar_w, y0, x0 + bar_w + 1, y0 + kLegendBarHeight, kText);
  append_text(mesh, x0, y0 - text_h - 3, content.legend_title, scale, kText);
  char lo[32], hi[32];
  std::snprintf(lo, sizeof lo, "%.3g", content.range_min);
  std::snprintf(hi, sizeof hi, "%.3g", content.range_max);
  append_text(mesh, x0, y0 + kLegendBarHeight + 3, lo, scale, kText);
  append_text(mesh, x0 + bar_w - text_width_px(hi, scale), y0 + kLegendBarHeight + 3, hi, scale, kText);
}

}  // namespace periflex
