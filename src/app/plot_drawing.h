// The window's plot: the shapes of render/plot_figure.h painted into a Dear ImGui draw list, with
// the text in the current ImGui font.
#pragma once

#include <imgui.h>

#include "render/plot_figure.h"

namespace periflex {

// A plot colour as Dear ImGui packs it.
ImU32 imgui_colour(Rgba8 c);

// Lays the plot out in the box at `origin` of `size` pixels and paints it; returns where its
// parts went. `scale` multiplies the margins and line widths (1 in the window).
PlotFrame draw_plot(ImDrawList& list, ImVec2 origin, ImVec2 size, const PlotHistory& history, const PlotView& view,
                    float scale = 1.0f);

}  // namespace periflex
