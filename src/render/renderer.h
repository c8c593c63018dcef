// Draws a Snapshot with OpenGL 3.3 core under whatever context is current: the GUI's
// window and the off-screen EGL framebuffer use this same code, so they show the same picture.
#pragma once

#include <memory>
#include <string>

#include "core/resources.h"
#include "render/camera.h"
#include "solve/snapshot.h"

namespace periflex {

enum class ColorField { kDamage, kDisplacement, kSpeed, kStrain };

struct RenderSettings {
  ColorField field = ColorField::kDamage;
  bool auto_range = true;          // range from the data each frame
  float range_min = 0.0f, range_max = 1.0f;
  std::string colormap = "turbo";  // a PNG in assets/colormaps/
  bool show_bodies = true;
  bool show_markers = true;
  bool show_springs = true;
  bool show_bonds = false;         // only small bodies carry bond pairs
  bool show_probes = true;
  bool show_trails = false;
  bool show_overlay = true;        // time, scene name, colour legend
  float particle_scale = 1.0f;     // disc diameter in grid spacings
  float background[3] = {0.12f, 0.12f, 0.14f};
};

class Renderer {
 public:
  // Loads shaders (shaders/) and colour maps (assets/) from the resource root.
  // Requires a current OpenGL 3.3 core context. Throws std::runtime_error with the path on failure.
  explicit Renderer(const std::string& resource_root);
  ~Renderer();

  // Draws the scene into the current framebuffer (viewport width x height pixels).
  void draw(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings,
            int width, int height);
  // Draws the overlay (time, scene name, colour legend) with Dear ImGui's draw lists;
  // call between ImGui::NewFrame() and ImGui::Render().
  void draw_overlay(const Snapshot& snapshot, const RenderSettings& settings, int width, int height);
  // Colour range used by the last draw (auto or fixed).
  float last_range_min() const;
  float last_range_max() const;
  std::vector<std::string> colormap_names() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
