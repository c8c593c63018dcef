// The text overlay over a picture (scene name, time and step, deformation factor, colour legend,
// scale bar) and a plot at the top right, laid out in pixels and drawn with the solid program.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "render/overlay_layout.h"

namespace periflex {

namespace {

using render_parts::use_flat_blending;

// The unit of a colour field, shown in the legend.
const char* field_unit(ColorField field) {
  switch (field) {
    case ColorField::kDamage: return "-";
    case ColorField::kDisplacement: return "m";
    case ColorField::kSpeed: return "m/s";
    case ColorField::kStrain: return "-";
  }
  return "-";
}

}  // namespace

void Renderer::draw_overlay(const Snapshot& snapshot, const RenderSettings& settings, int width, int height,
                            int left, const OverlayPlot* plot) {
  if (!settings.show_overlay) return;
  Impl& m = *impl_;

  // what the overlay says: scene name, time and step, the deformation factor when it is not 1
  OverlayContent content;
  if (snapshot.geometry && !snapshot.geometry->scene_name.empty())
    content.lines.push_back(snapshot.geometry->scene_name);
  char line[160];
  std::snprintf(line, sizeof line, "t = %.6g s   step %ld", snapshot.time, snapshot.step);
  content.lines.push_back(line);
  if (!snapshot.px.empty() && m.deform_used != 1.0) {
    std::snprintf(line, sizeof line, "deformation x%g%s", m.deform_used, settings.deform < 0.0f ? " (auto)" : "");
    content.lines.push_back(line);
  }
  content.pixel_world = m.pixel_world;
  content.legend = !snapshot.px.empty();
  content.legend_title = std::string(field_name(settings.field)) + " [" + field_unit(settings.field) + "]";
  content.range_min = m.range_min;
  content.range_max = m.range_max;
  content.colormap = &colormap_table(settings.colormap);

  // laid out in pixels (y down) and drawn with the solid-colour program over the picture
  m.mesh.clear();
  m.mesh.set_pixel_world(1.0);
  build_overlay(m.mesh, content, left, width, height);
  if (plot && plot->history) build_plot_overlay(m.mesh, *plot->history, plot->view, left, width, height);
  const float w = static_cast<float>(std::max(width, 1)), h = static_cast<float>(std::max(height, 1));
  const float pixels[16] = {2.0f / w, 0, 0, 0, 0, -2.0f / h, 0, 0, 0, 0, -1.0f, 0, -1.0f, 1.0f, 0, 1.0f};
  glViewport(0, 0, width, height);
  use_flat_blending();
  m.draw_mesh(pixels);
  m.mesh.set_pixel_world(m.pixel_world);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace periflex
