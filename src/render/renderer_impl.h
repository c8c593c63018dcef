// The renderer's inside, shared by the files of its passes (renderer.cpp holds the set-up, the
// colour maps and the frame): GL objects, the colour range, the magnified particle positions, the
// trails, the colours of the picture. Not a public header: only src/render includes it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "render/deformation.h"
#include "render/gl.h"
#include "render/renderer.h"
#include "render/solid_mesh.h"
#include "render/trails.h"

namespace periflex {
namespace render_parts {

// The fixed state of every pass: 2D (no depth test, no culling, no scissor) with straight alpha
// blending into a framebuffer whose alpha stays coverage.
inline void use_flat_blending() {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

// colours of the picture, chosen to stay readable over the dark default background
constexpr Rgba8 kGroundFill{78, 80, 88, 255}, kGroundEdge{140, 142, 150, 255};
constexpr Rgba8 kBodyEdge{225, 230, 240, 255};
constexpr Rgba8 kVirtualFill{240, 160, 60, 46}, kVirtualEdge{250, 175, 70, 230};
constexpr Rgba8 kJoint{245, 245, 245, 255}, kJointHole{30, 30, 34, 255};
constexpr Rgba8 kSlider{240, 220, 120, 255}, kDriver{255, 120, 60, 255}, kAttachment{230, 80, 230, 255};
constexpr Rgba8 kSpring{140, 220, 140, 255}, kBond{200, 200, 210, 110}, kProbe{255, 235, 60, 255};
constexpr Rgba8 kTrail{90, 200, 255, 255};
constexpr Rgba8 kContact{0, 255, 160, 255};
constexpr float kAttachedRing[4] = {0.95f, 0.3f, 0.95f, 1.0f};
// Below this disc diameter (pixels) a smoothed edge is mostly blur: plain squares instead.
constexpr double kDenseDiscPixels = 2.5;
// a few muted fills so neighbouring bodies can be told apart
constexpr Rgba8 kBodyFills[] = {{84, 120, 170, 255}, {150, 110, 80, 255}, {96, 140, 110, 255},
                                {130, 100, 150, 255}, {150, 140, 90, 255}, {90, 130, 140, 255}};

struct Colormap {
  GLuint texture = 0;
  std::vector<unsigned char> table;  // 256 x RGBA
};

inline const std::vector<float>* field_values(const Snapshot& s, ColorField f) {
  switch (f) {
    case ColorField::kDamage: return &s.damage;
    case ColorField::kDisplacement: return &s.displacement;
    case ColorField::kSpeed: return &s.speed;
    case ColorField::kStrain: return &s.strain;
  }
  return &s.damage;
}

}  // namespace render_parts

using render_parts::Colormap;

struct Renderer::Impl {
  GLuint particle_program = 0, dense_program = 0, solid_program = 0;
  GLint p_projection = -1, p_radius = -1, p_pixel_world = -1, p_range = -1, p_colormap = -1, p_solid = -1,
        p_ring = -1;
  GLint d_projection = -1, d_point_pixels = -1, d_range = -1, d_colormap = -1;
  GLint s_projection = -1;
  GLuint particle_vao = 0, particle_vbo = 0;
  GLuint attached_vao = 0, attached_vbo = 0;
  GLuint solid_vao = 0, solid_vbo = 0;
  std::map<std::string, Colormap> colormaps;
  std::vector<float> instances, attached;
  SolidMesh mesh;
  float range_min = 0.0f, range_max = 1.0f;
  std::string last_colormap = "ember";

  // particle positions drawn: the snapshot's, or magnified ones (render/deformation.h)
  std::vector<float> shown_x, shown_y;
  // how each body is drawn moved with its magnified particles (empty: where it is)
  std::vector<RigidShift> body_shift;
  double deform_used = 1.0;
  double pixel_world = 0.0;        // of the last draw, for the scale bar
  // the automatic factor only shrinks during a run, so a movie does not jump back and forth
  const SceneGeometry* deform_geometry = nullptr;
  double deform_time = -1e300;
  double auto_deform = kMaxAutoDeform;

  // trails: one polyline per rigid body centre and per probe (render/trails.h)
  Trails trails;

  void load_colormaps(const std::string& root);
  void make_buffers();
  const Colormap& colormap(const std::string& name) const;
  void update_range(const Snapshot& s, const RenderSettings& settings);
  void update_deformation(const Snapshot& s, const RenderSettings& settings);
  void draw_mesh(const float projection[16]);
  // the passes: particles (particle_pass.cpp), rigid bodies (body_pass.cpp), what is drawn over
  // them (marker_pass.cpp); the text overlay is Renderer::draw_overlay (overlay_pass.cpp)
  void draw_particles(const Snapshot& s, const RenderSettings& settings, const float projection[16],
                      double pixel_world);
  void build_bodies(const Snapshot& s, bool virtual_bodies);
  Vec2 shown_point(int body, const Vec2& p) const;
  void build_overlay_geometry(const Snapshot& s, const RenderSettings& settings);
};

}  // namespace periflex
