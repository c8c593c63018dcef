// Draws a Snapshot with OpenGL 3.3 core under whatever context is current: the GUI's
// window and the off-screen EGL framebuffer use this same code, so they show the same picture.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/resources.h"
#include "render/camera.h"
#include "render/plot_figure.h"
#include "solve/snapshot.h"

namespace periflex {

enum class ColorField { kDamage, kDisplacement, kSpeed, kStrain };

// Name shown in the legend and accepted on the command line: "damage", "displacement", "speed",
// "strain".
const char* field_name(ColorField field);
// Parses a name given by field_name; returns false when it is none of them.
bool parse_field_name(const std::string& name, ColorField& field);

// RenderSettings::deform asking for the automatic magnification
constexpr float kAutoDeform = -1.0f;

struct RenderSettings {
  ColorField field = ColorField::kDamage;
  bool auto_range = true;          // range from the data each frame
  float range_min = 0.0f, range_max = 1.0f;
  std::string colormap = "ember";  // a PNG in assets/colormaps/
  bool show_bodies = true;
  bool show_markers = true;
  bool show_springs = true;
  bool show_bonds = false;         // only small bodies carry bond pairs
  bool show_probes = true;
  bool show_trails = false;
  bool show_contacts = false;      // active contact points and their forces
  bool show_overlay = true;        // time, scene name, colour legend
  float particle_scale = 1.0f;     // disc diameter in grid spacings
  // Deformation magnification K (render/deformation.h): 1 true scale, 0 undeformed; negative
  // (kAutoDeform): chosen from the picture, never growing during a run.
  float deform = 1.0f;
  int trail_length = 400;          // points kept per trail (probes and rigid-body centres)
  float background[3] = {0.12f, 0.12f, 0.14f};
};

// A plot drawn over a picture, at the top right: the rows so far and what of them to show.
struct OverlayPlot {
  const PlotHistory* history = nullptr;
  PlotView view;
};

class Renderer {
 public:
  // Loads shaders (shaders/) and colour maps (assets/colormaps/*.png) from the resource root
  // (find_resource_root() gives the usual one).
  // Requires a current OpenGL 3.3 core context. Throws std::runtime_error with the path on failure.
  explicit Renderer(const std::string& resource_root);
  ~Renderer();

  // Draws the scene into the current framebuffer (viewport width x height pixels). Throws
  // std::runtime_error for an unknown colour map name (colormap_names() lists the valid ones).
  void draw(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings,
            int width, int height);
  // Draws the overlay (scene name, time, deformation factor, colour legend, scale bar) over the
  // current framebuffer (width x height pixels), after draw() of the same snapshot: the legend
  // shows the range that draw used. Text comes from the renderer's own glyph quads
  // (render/overlay_text.h), so any thread with a current context may call it. With left > 0 the
  // overlay keeps to the columns right of it (beside the window's panels). With a plot, the
  // plot too (render/plot_figure.h), so a recorded frame shows the plot the window shows.
  void draw_overlay(const Snapshot& snapshot, const RenderSettings& settings, int width, int height,
                    int left = 0, const OverlayPlot* plot = nullptr);
  // Colour range used by the last draw (auto or fixed).
  float last_range_min() const;
  float last_range_max() const;
  // Deformation magnification used by the last draw (the automatic one when asked).
  double last_deform() const;
  // Particle positions as the last draw placed them (magnified), for picking what is seen.
  const std::vector<float>& drawn_x() const;
  const std::vector<float>& drawn_y() const;
  std::vector<std::string> colormap_names() const;
  // The colour map as 256 RGBA entries (for legends drawn elsewhere); throws for unknown names.
  const std::vector<unsigned char>& colormap_table(const std::string& name) const;
  // Forgets the trails (also done automatically when time goes back or the scene changes).
  void clear_trails();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
