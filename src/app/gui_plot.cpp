// The plot window: any series.csv column (and the solver's steps/s) against time or against
// another column, with axes, ticks and units, a cursor at the time shown, zoom and pan along x,
// a readout under the pointer, and export of what is shown as CSV and PNG.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "app/gui_app.h"
#include "app/plot_axes.h"
#include "output/series_row.h"
#include "render/gl.h"
#include "io/image.h"

namespace periflex {

namespace {

// "kinetic [J]", or the bare name when the unit is not known
std::string axis_title(const std::string& column) {
  const std::string unit = series_unit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

// a column chooser; each choice is noted for input-driven tests as `<id>=<column>`
bool column_combo(const char* label, const char* id, std::string& chosen, const std::vector<std::string>& columns,
                  WidgetDump& dump) {
  bool changed = false;
  ImGui::SetNextItemWidth(200.0f);
  if (ImGui::BeginCombo(label, chosen.c_str(), ImGuiComboFlags_HeightLarge)) {
    for (const std::string& c : columns) {
      if (ImGui::Selectable(c.c_str(), c == chosen)) {
        changed = c != chosen;
        chosen = c;
      }
      dump.note_item(std::string(id) + "=" + c);
    }
    ImGui::EndCombo();
  }
  dump.note_item(id);
  return changed;
}

}  // namespace

void GuiApp::plot_window(int fb_width, int fb_height) {
  if (!show_plot_) return;
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x > 0.0f ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  // at the bottom of the picture beside the panels, clear of the colour legend, until moved
  ImGui::SetNextWindowPos(ImVec2(kPanelWidth / scale + 12.0f, std::max(40.0f, fb_height / scale - 440.0f)),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(std::min(620.0f, fb_width / scale - kPanelWidth / scale - 24.0f), 360.0f),
                           ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Plot", &show_plot_)) {
    ImGui::End();
    return;
  }
  const std::vector<std::string>& columns = history_.columns();
  // a column that this scene lacks falls back to time and kinetic energy
  if (!columns.empty() && history_.index_of(plot_x_) < 0) plot_x_ = "t";
  if (!columns.empty() && history_.index_of(plot_y_) < 0) plot_y_ = "kinetic";
  if (column_combo("y", "plot_y", plot_y_, columns, dump_)) plot_zoomed_ = false;
  ImGui::SameLine();
  if (column_combo("against", "plot_x", plot_x_, columns, dump_)) plot_zoomed_ = false;
  const int ix = history_.index_of(plot_x_), iy = history_.index_of(plot_y_);
  if (ix < 0 || iy < 0 || history_.size() == 0) {
    ImGui::TextUnformatted("no data yet");
    ImGui::End();
    return;
  }
  const std::vector<double>& xs = history_.values(ix);
  const std::vector<double>& ys = history_.values(iy);

  // x range: the whole history, or the zoomed part of it
  double data_lo = HUGE_VAL, data_hi = -HUGE_VAL;
  for (double v : xs) {
    if (!std::isfinite(v)) continue;
    data_lo = std::min(data_lo, v);
    data_hi = std::max(data_hi, v);
  }
  if (data_hi <= data_lo) {
    data_lo -= data_lo != 0.0 ? 0.05 * std::fabs(data_lo) : 1.0;
    data_hi = data_lo + (data_lo != 0.0 ? 0.1 * std::fabs(data_lo) : 2.0);
  }
  if (!plot_zoomed_) {
    plot_x_lo_ = data_lo;
    plot_x_hi_ = data_hi;
  }
  double y_lo = -1.0, y_hi = 1.0;
  visible_range(xs, ys, plot_x_lo_, plot_x_hi_, y_lo, y_hi);

  // the canvas: room on the left for the y ticks, below for the x ticks and the title
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 size(std::max(200.0f, avail.x), std::max(120.0f, avail.y - ImGui::GetFrameHeightWithSpacing()));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("plot_canvas", size);
  dump_.note_item("plot_canvas");
  const bool hovered = ImGui::IsItemHovered();
  const float left = 62.0f, bottom = 36.0f, top = 8.0f, right = 12.0f;
  const ImVec2 p0(origin.x + left, origin.y + top), p1(origin.x + size.x - right, origin.y + size.y - bottom);
  const auto to_x = [&](double v) { return p0.x + float((v - plot_x_lo_) / (plot_x_hi_ - plot_x_lo_)) * (p1.x - p0.x); };
  const auto to_y = [&](double v) { return p1.y - float((v - y_lo) / (y_hi - y_lo)) * (p1.y - p0.y); };
  const auto from_x = [&](float px) { return plot_x_lo_ + (px - p0.x) / (p1.x - p0.x) * (plot_x_hi_ - plot_x_lo_); };

  // zoom along x about the pointer (wheel), pan (left-drag), whole range again (double-click)
  ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0.0f) {
    const double at = from_x(io.MousePos.x), f = std::pow(0.85, io.MouseWheel);
    plot_x_lo_ = at + (plot_x_lo_ - at) * f;
    plot_x_hi_ = at + (plot_x_hi_ - at) * f;
    plot_zoomed_ = true;
  }
  if (ImGui::IsItemActive() && io.MouseDelta.x != 0.0f) {
    const double shift = -io.MouseDelta.x / (p1.x - p0.x) * (plot_x_hi_ - plot_x_lo_);
    plot_x_lo_ += shift;
    plot_x_hi_ += shift;
    plot_zoomed_ = true;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) plot_zoomed_ = false;

  ImDrawList* list = ImGui::GetWindowDrawList();
  const ImU32 axis = IM_COL32(200, 200, 200, 255), grid = IM_COL32(90, 90, 90, 120);
  const ImU32 line = IM_COL32(255, 190, 60, 255), cursor = IM_COL32(90, 220, 255, 255);
  list->AddRectFilled(p0, p1, IM_COL32(20, 22, 26, 255));
  // ticks and grid lines with their labels
  const std::vector<double> xt = nice_ticks(plot_x_lo_, plot_x_hi_, std::max(2, int((p1.x - p0.x) / 90.0f)));
  const std::vector<double> yt = nice_ticks(y_lo, y_hi, std::max(2, int((p1.y - p0.y) / 40.0f)));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double v : xt) {
    const float x = to_x(v);
    list->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), grid);
    list->AddLine(ImVec2(x, p1.y), ImVec2(x, p1.y + 4.0f), axis);
    const std::string label = tick_label(v, xstep);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    list->AddText(ImVec2(x - 0.5f * w, p1.y + 5.0f), axis, label.c_str());
  }
  for (double v : yt) {
    const float y = to_y(v);
    list->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), grid);
    list->AddLine(ImVec2(p0.x - 4.0f, y), ImVec2(p0.x, y), axis);
    const std::string label = tick_label(v, ystep);
    const ImVec2 ts = ImGui::CalcTextSize(label.c_str());
    list->AddText(ImVec2(p0.x - 6.0f - ts.x, y - 0.5f * ts.y), axis, label.c_str());
  }
  list->AddRect(p0, p1, axis);
  // axis titles with units: x below the ticks, y above the plot's left edge
  const std::string xtitle = axis_title(plot_x_), ytitle = axis_title(plot_y_);
  list->AddText(ImVec2(0.5f * (p0.x + p1.x) - 0.5f * ImGui::CalcTextSize(xtitle.c_str()).x, p1.y + 19.0f), axis,
                xtitle.c_str());
  list->AddText(ImVec2(p0.x + 6.0f, p0.y + 2.0f), line, ytitle.c_str());

  // the series, clipped to the frame
  list->PushClipRect(p0, p1, true);
  std::vector<ImVec2> points;
  points.reserve(xs.size());
  for (size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
    if (std::isfinite(xs[i]) && std::isfinite(ys[i])) points.emplace_back(to_x(xs[i]), to_y(ys[i]));
  }
  if (points.size() >= 2) list->AddPolyline(points.data(), static_cast<int>(points.size()), line, 0, 1.5f);
  // the instant shown: a vertical cursor against time, the latest point against another column
  if (plot_x_ == "t") {
    const float x = to_x(status_.time);
    list->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), cursor, 1.5f);
  } else if (!points.empty()) {
    list->AddCircle(points.back(), 5.0f, cursor, 0, 2.0f);
  }
  list->PopClipRect();

  // the point nearest the pointer along x, read out
  if (hovered && !points.empty()) {
    size_t best = 0;
    float distance = HUGE_VALF;
    for (size_t i = 0; i < points.size(); ++i) {
      const float d = std::fabs(points[i].x - io.MousePos.x) + (plot_x_ == "t" ? 0.0f : std::fabs(points[i].y - io.MousePos.y));
      if (d < distance) distance = d, best = i;
    }
    list->AddCircleFilled(points[best], 3.5f, cursor);
    size_t k = 0, seen = 0;
    for (; k < xs.size(); ++k)
      if (std::isfinite(xs[k]) && std::isfinite(ys[k]) && seen++ == best) break;
    if (k < xs.size()) ImGui::SetTooltip("%s = %.6g\n%s = %.6g", xtitle.c_str(), xs[k], ytitle.c_str(), ys[k]);
  }

  // export of what is shown: the points in the x range as CSV, the window's canvas as PNG
  ImGui::SetNextItemWidth(160.0f);
  ImGui::InputText("##plotfile", plot_path_, sizeof plot_path_);
  dump_.note_item("plot_file");
  ImGui::SameLine();
  if (ImGui::Button("Export CSV")) {
    const std::string path = std::string(plot_path_) + ".csv";
    std::ofstream out(path);
    out << plot_csv(plot_x_, plot_y_, xs, ys, plot_x_lo_, plot_x_hi_);
    out.close();
    plot_message_ = out ? "wrote " + path : "could not write " + path;
    log_.add("plot: " + plot_message_ + " (" + plot_y_ + " against " + plot_x_ + ")");
  }
  dump_.note_item("plot_csv");
  ImGui::SameLine();
  if (ImGui::Button("Export PNG")) {
    // read from the window after this frame is drawn (capture_plot)
    pending_plot_png_ = std::string(plot_path_) + ".png";
    plot_png_rect_ = {origin.x * scale, origin.y * scale, (origin.x + size.x) * scale, (origin.y + size.y) * scale};
  }
  dump_.note_item("plot_png");
  if (!plot_message_.empty()) {
    ImGui::SameLine();
    ImGui::TextUnformatted(plot_message_.c_str());
  }
  dump_.state("plot", plot_y_ + " " + plot_x_ + " " + std::to_string(points.size()));
  char range[80];
  std::snprintf(range, sizeof range, "%.9g %.9g", plot_x_lo_, plot_x_hi_);
  dump_.state("plot_range", range);
  ImGui::End();
}

void GuiApp::capture_plot(int fb_width, int fb_height) {
  // the canvas's pixels as drawn into the back buffer this frame
  const std::string path = pending_plot_png_;
  pending_plot_png_.clear();
  const int x0 = std::clamp(static_cast<int>(std::floor(plot_png_rect_[0])), 0, fb_width);
  const int y0 = std::clamp(static_cast<int>(std::floor(plot_png_rect_[1])), 0, fb_height);
  const int x1 = std::clamp(static_cast<int>(std::ceil(plot_png_rect_[2])), 0, fb_width);
  const int y1 = std::clamp(static_cast<int>(std::ceil(plot_png_rect_[3])), 0, fb_height);
  if (x1 - x0 < 2 || y1 - y0 < 2) {
    plot_message_ = "the plot is not on screen";
    log_.add("plot: " + plot_message_);
    return;
  }
  RgbaImage image;
  image.resize(x1 - x0, y1 - y0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(x0, fb_height - y1, x1 - x0, y1 - y0, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  flip_rows(image);
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  try {
    write_png(path, image);
    plot_message_ = "wrote " + path;
  } catch (const std::exception& e) {
    plot_message_ = std::string("could not write the plot: ") + e.what();
  }
  log_.add("plot: " + plot_message_ + " (" + std::to_string(x1 - x0) + "x" + std::to_string(y1 - y0) + ")");
}

}  // namespace periflex
