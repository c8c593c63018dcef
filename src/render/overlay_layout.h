// Where the overlay's parts go on a picture, in pixels from its top-left corner: the scene name,
// time and deformation factor at the top left, a scale bar at the bottom right, the colour
// legend at the bottom left. Builds triangles only; the renderer draws them (no GL here).
#pragma once

#include <string>
#include <vector>

#include "render/plot_figure.h"
#include "render/solid_mesh.h"

namespace periflex {

struct OverlayContent {
  std::vector<std::string> lines;   // top left, one per line
  double pixel_world = 0.0;         // metres per pixel; no scale bar unless positive and finite
  bool legend = false;              // the colour legend (pictures with particles)
  std::string legend_title;         // "damage [-]"
  float range_min = 0.0f, range_max = 1.0f;
  const std::vector<unsigned char>* colormap = nullptr;  // 256 RGBA entries
};

// Margins and sizes of the layout, in pixels.
constexpr int kOverlayMargin = 6;        // from the picture's edges to the shaded boxes
constexpr int kOverlayPad = 4;           // inside the boxes, around the text
constexpr int kOverlayLineGap = 3;       // between lines of text
constexpr int kLegendBarHeight = 12;
constexpr int kLegendBarMaxWidth = 220;

// A length in the unit that reads best: "20 mm", "500 um", "2 m".
std::string format_length(double metres);

// Where a picture's plot goes: the top right, beside the text at the top left and above the
// legend and scale bar at the bottom. Origin and size in pixels.
void plot_box(int left, int width, int height, PlotPoint& origin, PlotPoint& size);

// Appends the plot of `history` as `view` says, laid out in plot_box (render/plot_figure.h), with
// the overlay's text.
void build_plot_overlay(SolidMesh& mesh, const PlotHistory& history, const PlotView& view, int left, int width,
                        int height);

// Appends the overlay for a picture occupying columns [left, width) of a width x height target
// (left > 0 keeps it beside a panel column). Text scale from overlay_text_scale.
void build_overlay(SolidMesh& mesh, const OverlayContent& content, int left, int width, int height);

}  // namespace periflex
