// A 2D camera: a centre in world coordinates and the world height the viewport shows.
// Pan by dragging, zoom about the cursor, fit to the scene, follow a body.
#pragma once

#include "core/vec2.h"

namespace periflex {

struct Camera {
  Vec2 center = Vec2::Zero();
  double view_height = 2.0;  // world units from bottom to top of the viewport

  // Frame the box [lo, hi] with a margin, for a viewport of the given aspect (width / height).
  void fit(const Vec2& lo, const Vec2& hi, double aspect, double margin = 0.08);
  // Move by a drag of (dx, dy) pixels in a viewport of height_px pixels.
  void pan_pixels(double dx_px, double dy_px, int height_px);
  // Zoom by factor (>1 zooms in) keeping the world point under the cursor fixed.
  void zoom_at(double factor, double cursor_x_px, double cursor_y_px, int width_px, int height_px);
  // Pixel (origin top-left) to world, and back.
  Vec2 to_world(double x_px, double y_px, int width_px, int height_px) const;
  Vec2 to_pixels(const Vec2& world, int width_px, int height_px) const;
  // Column-major 4x4 orthographic matrix for a viewport of the given aspect.
  void projection(double aspect, float out[16]) const;
};

}  // namespace periflex
