// The plot window: any series.csv columns (and the solver's steps/s), one or several, against
// time or against another column, with axes, ticks, units and a legend (app/plot_drawing.h),
// a cursor at the time shown, zoom and pan along x, a readout under the pointer, and export of
// what is shown as CSV (one column per series) and PNG.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "app/gui_app.h"
#include "render/plot_axes.h"
#include "app/plot_drawing.h"
#include "render/gl.h"
#include "io/image.h"

namespace periflex {

namespace {

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

PlotView GuiApp::plot_view(double cursor_time) const {
  PlotView view;
  view.x_column = plot_x_;
  view.y_columns = {plot_y_};
  view.y_columns.insert(view.y_columns.end(), plot_more_.begin(), plot_more_.end());
  view.cursor_time = cursor_time;
  return view;
}

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
  // a column that this scene lacks falls back to time and kinetic energy; further series it
  // lacks are dropped
  if (!columns.empty() && history_.index_of(plot_x_) < 0) plot_x_ = "t";
  if (!columns.empty() && history_.index_of(plot_y_) < 0) plot_y_ = "kinetic";
  if (!columns.empty())
    std::erase_if(plot_more_, [&](const std::string& c) { return history_.index_of(c) < 0 || c == plot_y_; });
  if (column_combo("y", "plot_y", plot_y_, columns, dump_)) plot_zoomed_ = false;
  ImGui::SameLine();
  if (column_combo("against", "plot_x", plot_x_, columns, dump_)) plot_zoomed_ = false;
  // another series in the same plot, and the ones added, each with its remove button
  std::string added = "+ series";
  ImGui::SameLine();
  if (column_combo("##plot_add", "plot_add", added, columns, dump_) && added != plot_y_ &&
      std::find(plot_more_.begin(), plot_more_.end(), added) == plot_more_.end())
    plot_more_.push_back(added);
  for (size_t k = 0; k < plot_more_.size(); ++k) {
    if (k > 0) ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_Text, imgui_colour(plot_colour(k + 1)));
    const bool remove = ImGui::SmallButton(("x " + plot_more_[k]).c_str());
    ImGui::PopStyleColor();
    dump_.note_item("plot_remove=" + plot_more_[k]);
    if (remove) {
      plot_more_.erase(plot_more_.begin() + static_cast<long>(k));
      break;
    }
  }
  PlotView view = plot_view(status_.time);
  double data_lo = 0.0, data_hi = 1.0;
  if (history_.index_of(plot_x_) < 0 || history_.index_of(plot_y_) < 0 || history_.size() == 0 ||
      !plot_column_range(history_, plot_x_, data_lo, data_hi)) {
    ImGui::TextUnformatted("no data yet");
    ImGui::End();
    return;
  }
  const std::vector<double>& xs = history_.values(history_.index_of(plot_x_));

  // x range: the whole history, or the zoomed part of it
  if (!plot_zoomed_) {
    plot_x_lo_ = data_lo;
    plot_x_hi_ = data_hi;
  }

  // the canvas: the shared plot drawing (app/plot_drawing.h) fills it
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 size(std::max(200.0f, avail.x), std::max(120.0f, avail.y - ImGui::GetFrameHeightWithSpacing()));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("plot_canvas", size);
  dump_.note_item("plot_canvas");
  const bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  view.x_lo = plot_x_lo_;
  view.x_hi = plot_x_hi_;
  const PlotFrame frame = draw_plot(*ImGui::GetWindowDrawList(), origin, size, history_, view);
  const PlotPoint p0 = frame.p0, p1 = frame.p1;
  const auto from_x = [&](float px) { return plot_x_lo_ + (px - p0.x) / (p1.x - p0.x) * (plot_x_hi_ - plot_x_lo_); };

  // zoom along x about the pointer (wheel), pan (left-drag), whole range again (double-click);
  // taking effect from the next frame
  ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0.0f) {
    const double at = from_x(io.MousePos.x), f = std::pow(0.85, io.MouseWheel);
    plot_x_lo_ = at + (plot_x_lo_ - at) * f;
    plot_x_hi_ = at + (plot_x_hi_ - at) * f;
    plot_zoomed_ = true;
  }
  if (active && io.MouseDelta.x != 0.0f) {
    const double shift = -io.MouseDelta.x / (p1.x - p0.x) * (plot_x_hi_ - plot_x_lo_);
    plot_x_lo_ += shift;
    plot_x_hi_ += shift;
    plot_zoomed_ = true;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) plot_zoomed_ = false;

  // the point nearest the pointer along x (of any series), read out
  if (hovered) {
    size_t best_series = 0, best = 0;
    float distance = HUGE_VALF;
    for (size_t k = 0; k < frame.points.size(); ++k) {
      for (size_t i = 0; i < frame.points[k].size(); ++i) {
        const PlotPoint p = frame.points[k][i];
        const float d = std::fabs(p.x - io.MousePos.x) + (plot_x_ == "t" && frame.points.size() == 1
                                                              ? 0.0f
                                                              : std::fabs(p.y - io.MousePos.y));
        if (d < distance) distance = d, best_series = k, best = i;
      }
    }
    if (distance < HUGE_VALF) {
      const PlotPoint nearest = frame.points[best_series][best];
      ImGui::GetWindowDrawList()->AddCircleFilled(ImVec2(nearest.x, nearest.y), 3.5f, IM_COL32(90, 220, 255, 255));
      const size_t row = frame.rows[best_series][best];
      const std::string& y = view.y_columns[best_series];
      ImGui::SetTooltip("%s = %.6g\n%s = %.6g", plot_axis_title(plot_x_).c_str(), xs[row],
                        plot_axis_title(y).c_str(), history_.values(history_.index_of(y))[row]);
    }
  }

  // export of what is shown: the points in the x range as CSV (one column per series), the
  // window's canvas as PNG
  ImGui::SetNextItemWidth(160.0f);
  ImGui::InputText("##plotfile", plot_path_, sizeof plot_path_);
  dump_.note_item("plot_file");
  ImGui::SameLine();
  if (ImGui::Button("Export CSV")) {
    const std::string path = std::string(plot_path_) + ".csv";
    std::vector<const std::vector<double>*> ys;
    for (const std::string& c : view.y_columns) ys.push_back(&history_.values(history_.index_of(c)));
    std::ofstream out(path);
    out << plot_csv(plot_x_, xs, view.y_columns, ys, plot_x_lo_, plot_x_hi_);
    out.close();
    plot_message_ = out ? "wrote " + path : "could not write " + path;
    std::string what;
    for (const std::string& c : view.y_columns) what += (what.empty() ? "" : ", ") + c;
    log_.add("plot: " + plot_message_ + " (" + what + " against " + plot_x_ + ")");
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
  const size_t shown = frame.points.empty() ? 0 : frame.points.front().size();
  dump_.state("plot", plot_y_ + " " + plot_x_ + " " + std::to_string(shown));
  std::string series;
  for (const std::string& c : view.y_columns) series += (series.empty() ? "" : " ") + c;
  dump_.state("plot_series", series);
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
