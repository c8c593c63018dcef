#include "app/plot_drawing.h"

#include <cfloat>

namespace periflex {

ImU32 imgui_colour(Rgba8 c) { return IM_COL32(c.r, c.g, c.b, c.a); }

PlotFrame draw_plot(ImDrawList& list, ImVec2 origin, ImVec2 size, const PlotHistory& history, const PlotView& view,
                    float scale) {
  ImFont* font = ImGui::GetFont();
  const float font_size = ImGui::GetFontSize() * scale;
  PlotTextMetrics metrics;
  metrics.width = [&](const std::string& s) { return font->CalcTextSizeA(font_size, FLT_MAX, 0.0f, s.c_str()).x; };
  metrics.height = font_size;
  const PlotFigure figure = layout_plot({origin.x, origin.y}, {size.x, size.y}, history, view, metrics, scale);

  const auto at = [](PlotPoint p) { return ImVec2(p.x, p.y); };
  std::vector<ImVec2> points;
  for (const PlotShape& s : figure.shapes) {
    const ImU32 colour = imgui_colour(s.colour);
    switch (s.kind) {
      case PlotShape::Kind::kFill: list.AddRectFilled(at(s.points[0]), at(s.points[1]), colour); break;
      case PlotShape::Kind::kOutline: list.AddRect(at(s.points[0]), at(s.points[1]), colour, 0.0f, 0, s.width); break;
      case PlotShape::Kind::kLine:
        points.clear();
        for (PlotPoint p : s.points) points.push_back(at(p));
        list.AddPolyline(points.data(), static_cast<int>(points.size()), colour, 0, s.width);
        break;
      case PlotShape::Kind::kRing: list.AddCircle(at(s.points[0]), s.radius, colour, 0, s.width); break;
      case PlotShape::Kind::kText: list.AddText(font, font_size, at(s.points[0]), colour, s.text.c_str()); break;
    }
  }
  return figure.frame;
}

}  // namespace periflex
