// Triangles with a colour per vertex, built on the CPU each frame: body shapes and outlines,
// markers, springs, bonds, probes and trails. Widths and marker sizes are given in pixels and
// turned into world units with the current zoom, so lines keep their thickness when zooming.
// Everything is triangles because core-profile OpenGL does not promise lines wider than a pixel.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec2.h"
#include "scene/scene_def.h"
#include "scene/shape_outline.h"

namespace periflex {

struct Rgba8 {
  uint8_t r = 255, g = 255, b = 255, a = 255;
};

// 12 bytes: world position and colour (normalised bytes in the shader).
struct SolidVertex {
  float x, y;
  uint8_t r, g, b, a;
};

class SolidMesh {
 public:
  // world size of one pixel; widths in pixels are multiplied by it
  void set_pixel_world(double pixel_world) { px_ = pixel_world; }
  double pixel_world() const { return px_; }
  void clear() { vertices_.clear(); }
  const std::vector<SolidVertex>& vertices() const { return vertices_; }

  void triangle(const Vec2& a, const Vec2& b, const Vec2& c, Rgba8 color);
  // Fills any simple polygon (either winding) by ear clipping.
  void fill_polygon(const std::vector<Vec2>& points, Rgba8 color);
  // A segment width_px pixels wide.
  void line(const Vec2& a, const Vec2& b, double width_px, Rgba8 color);
  // Joined segments with mitred corners (limited so sharp corners do not spike).
  void polyline(const std::vector<Vec2>& points, bool closed, double width_px, Rgba8 color);
  // Dashes of dash_px separated by gap_px, measured along the path.
  void dashed_polyline(const std::vector<Vec2>& points, bool closed, double width_px, double dash_px,
                       double gap_px, Rgba8 color);
  // Filled disc; radius in world units.
  void disc(const Vec2& center, double radius, Rgba8 color, int segments = 24);
  // Disc and ring whose radius is in pixels (markers).
  void disc_px(const Vec2& center, double radius_px, Rgba8 color) { disc(center, radius_px * px_, color, 16); }
  void ring_px(const Vec2& center, double radius_px, double width_px, Rgba8 color);
  // A square or diamond marker of half-size half_px pixels.
  void square_px(const Vec2& center, double half_px, Rgba8 color, bool diamond = false);
  // An x-shaped cross.
  void cross_px(const Vec2& center, double half_px, double width_px, Rgba8 color);
  // A spring: short straight ends and `zigs` teeth of the given amplitude (world units) between.
  void zigzag(const Vec2& a, const Vec2& b, int zigs, double amplitude, double width_px, Rgba8 color);

 private:
  void push(const Vec2& p, Rgba8 c) {
    vertices_.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()), c.r, c.g, c.b, c.a});
  }
  double px_ = 1.0;
  std::vector<SolidVertex> vertices_;
};

// Triangles (indices into points) covering a simple polygon of either winding; a polygon with
// fewer than three points gives none. Degenerate input falls back to a fan.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& points);


}  // namespace periflex
