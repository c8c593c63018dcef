#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "render/deformation.h"
#include "render/gl.h"
#include "io/image.h"
#include "render/overlay_layout.h"
#include "render/solid_mesh.h"

namespace periflex {

namespace fs = std::filesystem;

const char* field_name(ColorField field) {
  switch (field) {
    case ColorField::kDamage: return "damage";
    case ColorField::kDisplacement: return "displacement";
    case ColorField::kSpeed: return "speed";
    case ColorField::kStrain: return "strain";
  }
  return "damage";
}

bool parse_field_name(const std::string& name, ColorField& field) {
  for (ColorField f : {ColorField::kDamage, ColorField::kDisplacement, ColorField::kSpeed, ColorField::kStrain}) {
    if (name == field_name(f)) {
      field = f;
      return true;
    }
  }
  return false;
}

namespace {

// The fixed state of every pass: 2D (no depth test, no culling, no scissor) with straight alpha
// blending into a framebuffer whose alpha stays coverage.
void use_flat_blending() {
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

const std::vector<float>* field_values(const Snapshot& s, ColorField f) {
  switch (f) {
    case ColorField::kDamage: return &s.damage;
    case ColorField::kDisplacement: return &s.displacement;
    case ColorField::kSpeed: return &s.speed;
    case ColorField::kStrain: return &s.strain;
  }
  return &s.damage;
}

}  // namespace

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


  // trails: one polyline per rigid body centre and per probe
  const SceneGeometry* trail_geometry = nullptr;
  double trail_time = -1e300;
  std::vector<std::deque<Vec2>> trails;

  void load_colormaps(const std::string& root);
  void make_buffers();
  const Colormap& colormap(const std::string& name) const;
  void update_range(const Snapshot& s, const RenderSettings& settings);
  void record_trails(const Snapshot& s, int max_points);
  void update_deformation(const Snapshot& s, const RenderSettings& settings);
  void draw_mesh(const float projection[16]);
  void draw_particles(const Snapshot& s, const RenderSettings& settings, const float projection[16],
                      double pixel_world);
  void build_bodies(const Snapshot& s, bool virtual_bodies);
  Vec2 shown_point(int body, const Vec2& p) const;
  void build_overlay_geometry(const Snapshot& s, const RenderSettings& settings);
};

void Renderer::Impl::load_colormaps(const std::string& root) {
  const fs::path dir = fs::path(root) / "assets" / "colormaps";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() != ".png") continue;
    // resample any width to 256 entries (nearest), one row is enough
    const RgbaImage image = read_png(entry.path().string());
    Colormap cm;
    cm.table.resize(256 * 4);
    for (int i = 0; i < 256; ++i) {
      const int x = std::min(image.width - 1, i * image.width / 256);
      std::copy(image.at(x, 0), image.at(x, 0) + 4, cm.table.begin() + 4 * i);
    }
    glGenTextures(1, &cm.texture);
    glBindTexture(GL_TEXTURE_2D, cm.texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 256, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, cm.table.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    colormaps[entry.path().stem().string()] = std::move(cm);
  }
  if (ec || colormaps.empty())
    throw std::runtime_error("no colour maps found in " + dir.string() + " (is PERIFLEX_ROOT right?)");
}

void Renderer::Impl::make_buffers() {
  // particles are points (one vertex each) sized in the vertex shader
  for (auto [vao, vbo] : {std::pair{&particle_vao, &particle_vbo}, std::pair{&attached_vao, &attached_vbo}}) {
    glGenVertexArrays(1, vao);
    glGenBuffers(1, vbo);
    glBindVertexArray(*vao);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  }

  glGenVertexArrays(1, &solid_vao);
  glGenBuffers(1, &solid_vbo);
  glBindVertexArray(solid_vao);
  glBindBuffer(GL_ARRAY_BUFFER, solid_vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(SolidVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(SolidVertex),
                        reinterpret_cast<const void*>(offsetof(SolidVertex, r)));
  glBindVertexArray(0);
}

const Colormap& Renderer::Impl::colormap(const std::string& name) const {
  auto it = colormaps.find(name);
  if (it == colormaps.end()) {
    std::string known;
    for (const auto& [n, cm] : colormaps) known += (known.empty() ? "" : ", ") + n;
    throw std::runtime_error("unknown colour map '" + name + "' (available: " + known + ")");
  }
  return it->second;
}

void Renderer::Impl::update_range(const Snapshot& s, const RenderSettings& settings) {
  if (!settings.auto_range) {
    range_min = settings.range_min;
    range_max = settings.range_max;
    return;
  }
  // damage is a fraction of broken bonds, so its natural range is always [0, 1]
  if (settings.field == ColorField::kDamage) {
    range_min = 0.0f;
    range_max = 1.0f;
    return;
  }
  const std::vector<float>& v = *field_values(s, settings.field);
  if (v.empty()) {
    range_min = 0.0f;
    range_max = 1.0f;
    return;
  }
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  range_min = *lo;
  range_max = *hi;
  // a uniform field still needs a non-empty span
  if (!(range_max > range_min)) range_max = range_min + std::max(1e-6f, std::abs(range_min) * 1e-3f);
}

void Renderer::Impl::update_deformation(const Snapshot& s, const RenderSettings& settings) {
  double factor = settings.deform;
  if (factor < 0.0) {
    // start over when the scene changes or time runs backwards (reset, reload)
    if (s.geometry.get() != deform_geometry || s.time < deform_time) auto_deform = kMaxAutoDeform;
    deform_geometry = s.geometry.get();
    deform_time = s.time;
    auto_deform = std::min(auto_deform, auto_deform_factor(s));
    factor = s.geometry && s.geometry->has_particles() ? auto_deform : 1.0;
  }
  deform_used = factor;
  if (factor == 1.0) {
    shown_x = s.px;
    shown_y = s.py;
    body_shift.clear();
  } else {
    magnify_deformation(s, factor, shown_x, shown_y);
    body_shift = magnified_body_shifts(s, shown_x, shown_y);
  }
}

// a point carried by geometry body `body`, where the drawing shows it
Vec2 Renderer::Impl::shown_point(int body, const Vec2& p) const {
  return body > 0 && static_cast<size_t>(body) < body_shift.size() ? body_shift[body].apply(p) : p;
}

void Renderer::Impl::record_trails(const Snapshot& s, int max_points) {
  // start over when the scene changes or time runs backwards (reset, reload)
  if (s.geometry.get() != trail_geometry || s.time < trail_time) {
    trails.clear();
    trail_geometry = s.geometry.get();
  }
  trail_time = s.time;
  std::vector<Vec2> points;
  if (s.geometry) {
    const size_t nb = std::min(s.geometry->bodies.size(), s.bodies.size());
    for (size_t k = 0; k < nb; ++k)
      if (!s.geometry->bodies[k].ground) points.emplace_back(s.bodies[k].x, s.bodies[k].y);
  }
  for (const auto& p : s.probes) points.push_back(p.position);
  if (trails.size() != points.size()) trails.assign(points.size(), {});
  for (size_t i = 0; i < points.size(); ++i) {
    auto& t = trails[i];
    if (!t.empty() && (t.back() - points[i]).squaredNorm() == 0.0) continue;
    t.push_back(points[i]);
    while (static_cast<int>(t.size()) > std::max(2, max_points)) t.pop_front();
  }
}

void Renderer::Impl::draw_mesh(const float projection[16]) {
  const auto& v = mesh.vertices();
  if (v.empty()) return;
  glUseProgram(solid_program);
  glUniformMatrix4fv(s_projection, 1, GL_FALSE, projection);
  glBindVertexArray(solid_vao);
  glBindBuffer(GL_ARRAY_BUFFER, solid_vbo);
  glBufferData(GL_ARRAY_BUFFER, v.size() * sizeof(SolidVertex), v.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
  mesh.clear();
}

void Renderer::Impl::draw_particles(const Snapshot& s, const RenderSettings& settings, const float projection[16],
                                    double pixel_world) {
  const size_t n = std::min(shown_x.size(), shown_y.size());
  if (n == 0) return;
  // interleave x, y and the field value: 12 bytes per particle, one upload per frame
  const std::vector<float>& field = *field_values(s, settings.field);
  instances.resize(3 * n);
  const bool has_field = field.size() >= n;
  for (size_t i = 0; i < n; ++i) {
    instances[3 * i] = shown_x[i];
    instances[3 * i + 1] = shown_y[i];
    instances[3 * i + 2] = has_field ? field[i] : 0.0f;
  }
  glUseProgram(particle_program);
  glUniformMatrix4fv(p_projection, 1, GL_FALSE, projection);
  glUniform1f(p_pixel_world, static_cast<float>(pixel_world));
  glUniform2f(p_range, range_min, range_max);
  glUniform1i(p_colormap, 0);
  glUniform4f(p_solid, 0.f, 0.f, 0.f, 0.f);
  glUniform1f(p_ring, 0.f);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, colormap(settings.colormap).texture);
  glBindVertexArray(particle_vao);
  glBindBuffer(GL_ARRAY_BUFFER, particle_vbo);
  glBufferData(GL_ARRAY_BUFFER, instances.size() * sizeof(float), instances.data(), GL_STREAM_DRAW);

  // one draw per flexible body, each with its own disc size
  glEnable(GL_PROGRAM_POINT_SIZE);
  auto draw_range = [&](size_t first, size_t count, double spacing) {
    if (count == 0) return;
    const double radius = 0.5 * spacing * settings.particle_scale;
    glUniform1f(p_radius, static_cast<float>(radius));
    // discs under kDenseDiscPixels across: opaque squares as wide as the disc, no blending
    const double disc_pixels = 2.0 * radius / pixel_world;
    if (spacing > 0.0 && disc_pixels < kDenseDiscPixels) {
      glUseProgram(dense_program);
      glUniformMatrix4fv(d_projection, 1, GL_FALSE, projection);
      glUniform2f(d_range, range_min, range_max);
      glUniform1i(d_colormap, 0);
      glUniform1f(d_point_pixels, static_cast<float>(std::max(1.0, std::ceil(disc_pixels))));
      glDisable(GL_BLEND);
      glDisable(GL_MULTISAMPLE);
      glDrawArrays(GL_POINTS, static_cast<GLint>(first), static_cast<GLsizei>(count));
      glEnable(GL_MULTISAMPLE);
      glEnable(GL_BLEND);
      glUseProgram(particle_program);
      return;
    }
    glDrawArrays(GL_POINTS, static_cast<GLint>(first), static_cast<GLsizei>(count));
  };
  if (s.geometry && !s.geometry->flex_bodies.empty()) {
    for (const auto& fb : s.geometry->flex_bodies) {
      const size_t first = std::min<size_t>(fb.first_particle, n);
      draw_range(first, std::min<size_t>(fb.particle_count, n - first), fb.grid_spacing);
    }
  } else {
    draw_range(0, n, 0.0);  // no geometry: discs of about a pixel
  }

  // rings around particles held by rigid-flexible joints
  if (!settings.show_markers || !s.geometry || s.geometry->particle_attached.empty()) return;
  attached.clear();
  double spacing = 0.0;
  for (const auto& fb : s.geometry->flex_bodies) spacing = std::max(spacing, fb.grid_spacing);
  const auto& flags = s.geometry->particle_attached;
  for (size_t i = 0; i < std::min(n, flags.size()); ++i)
    if (flags[i]) attached.insert(attached.end(), {shown_x[i], shown_y[i], 0.0f});
  if (attached.empty()) return;
  glBindVertexArray(attached_vao);
  glBindBuffer(GL_ARRAY_BUFFER, attached_vbo);
  glBufferData(GL_ARRAY_BUFFER, attached.size() * sizeof(float), attached.data(), GL_STREAM_DRAW);
  const float radius = static_cast<float>(std::max(0.5 * spacing * settings.particle_scale, 2.5 * pixel_world));
  glUniform1f(p_radius, radius);
  glUniform4fv(p_solid, 1, kAttachedRing);
  glUniform1f(p_ring, std::clamp(static_cast<float>(1.5 * pixel_world / radius), 0.15f, 0.6f));
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(attached.size() / 3));
}

void Renderer::Impl::build_bodies(const Snapshot& s, bool virtual_bodies) {
  if (!s.geometry) return;
  const size_t nb = std::min(s.geometry->bodies.size(), s.bodies.size());
  for (size_t k = 0; k < nb; ++k) {
    const SceneGeometry::Body& body = s.geometry->bodies[k];
    if (body.is_virtual != virtual_bodies) continue;
    const Snapshot::Pose& pose = s.bodies[k];
    // a virtual body moves with its magnified particles (identity otherwise)
    const Vec2 position = shown_point(static_cast<int>(k), Vec2(pose.x, pose.y));
    const double angle = pose.angle + (k < body_shift.size() ? body_shift[k].angle : 0.0);
    for (const ShapeDef& shape : body.shapes) {
      const std::vector<Vec2> outline = shape_outline(shape, position, angle);
      if (outline.size() < 2) continue;
      if (body.is_virtual) {
        // virtual bodies: see-through fill, dashed edge
        mesh.fill_polygon(outline, kVirtualFill);
        mesh.dashed_polyline(outline, true, 1.5, 6.0, 4.0, kVirtualEdge);
      } else if (body.ground) {
        mesh.fill_polygon(outline, kGroundFill);
        mesh.polyline(outline, true, 1.5, kGroundEdge);
      } else {
        mesh.fill_polygon(outline, kBodyFills[k % std::size(kBodyFills)]);
        mesh.polyline(outline, true, 1.5, kBodyEdge);
      }
      // a radius line shows how circles turn
      if (shape.kind == ShapeDef::Kind::kCircle && !body.ground)
        mesh.line(position + rotation(angle) * shape.center,
                  position + rotation(angle) * (shape.center + Vec2(shape.radius, 0.0)), 1.5,
                  body.is_virtual ? kVirtualEdge : kBodyEdge);
    }
  }
}

void Renderer::Impl::build_overlay_geometry(const Snapshot& s, const RenderSettings& settings) {
  // bonds: thin translucent lines between the particles of small bodies
  if (settings.show_bonds) {
    const size_t n = std::min(shown_x.size(), shown_y.size());
    for (const auto& [i, j] : s.bond_pairs) {
      if (i < 0 || j < 0 || size_t(i) >= n || size_t(j) >= n) continue;
      mesh.line(Vec2(shown_x[i], shown_y[i]), Vec2(shown_x[j], shown_y[j]), 1.0, kBond);
    }
  }
  if (settings.show_bodies) build_bodies(s, true);
  if (settings.show_springs) {
    for (const auto& sp : s.springs) {
      const double len = (sp.b - sp.a).norm();
      const double amplitude = std::min(0.08 * len, 8.0 * mesh.pixel_world());
      mesh.zigzag(sp.a, sp.b, 10, amplitude, 1.5, kSpring);
    }
  }
  // trails fade from transparent (old) to opaque (new)
  if (settings.show_trails) {
    for (const auto& t : trails) {
      const size_t m = t.size();
      for (size_t i = 1; i < m; ++i) {
        Rgba8 c = kTrail;
        c.a = static_cast<uint8_t>(40 + 215 * i / m);
        mesh.line(t[i - 1], t[i], 1.5, c);
      }
    }
  }
  if (settings.show_markers) {
    using Kind = Snapshot::Marker::Kind;
    for (const auto& marker : s.markers) {
      // markers on a virtual body move with it
      // (a joint drawn at one point, between a virtual body and another, is drawn on the virtual one)
      Snapshot::Marker m = marker;
      const auto moves = [&](int b) { return b > 0 && static_cast<size_t>(b) < body_shift.size() && body_shift[b].moves; };
      const bool one_point = m.kind == Kind::kRevolute || m.kind == Kind::kRigid;
      m.a = !one_point || moves(marker.body_a) || !moves(marker.body_b) ? shown_point(marker.body_a, marker.a)
                                                                        : shown_point(marker.body_b, marker.b);
      m.b = shown_point(marker.body_b, marker.b);
      switch (m.kind) {
        case Kind::kRevolute:
          mesh.disc_px(m.a, 4.5, kJoint);
          mesh.disc_px(m.a, 2.0, kJointHole);
          break;
        case Kind::kTranslational:
          mesh.dashed_polyline({m.a, m.b}, false, 1.5, 5.0, 3.0, kSlider);
          mesh.square_px(m.a, 3.5, kSlider);
          break;
        case Kind::kRigid:
          mesh.square_px(m.a, 3.5, kJoint);
          break;
        case Kind::kLink:
          mesh.line(m.a, m.b, 2.0, kJoint);
          mesh.ring_px(m.a, 4.0, 1.5, kJoint);
          mesh.ring_px(m.b, 4.0, 1.5, kJoint);
          break;
        case Kind::kDriver:
          mesh.ring_px(m.a, 7.0, 2.0, kDriver);
          mesh.disc_px(m.a, 2.5, kDriver);
          break;
        case Kind::kAttachment:
          mesh.square_px(m.a, 5.0, kAttachment, true);
          break;
      }
    }
  }
  // probes on what carries them: a particle's magnified place, a virtual body's shifted one
  if (settings.show_probes)
    for (const auto& p : s.probes)
      mesh.cross_px(deform_used == 1.0 ? p.position : magnified_probe(p, shown_x, shown_y, body_shift), 4.0, 1.5,
                    kProbe);
  // active contacts: a dot where each acts and a stroke along its force, 6 to 24 px long by its
  // share of the largest force
  if (settings.show_contacts && !s.contacts.empty()) {
    double largest = 0.0;
    for (const auto& c : s.contacts) largest = std::max(largest, c.force.norm());
    for (const auto& c : s.contacts) {
      const double f = c.force.norm();
      mesh.disc_px(c.point, 2.5, kContact);
      if (f > 0.0 && largest > 0.0)
        mesh.line(c.point, c.point + c.force / f * ((6.0 + 18.0 * f / largest) * mesh.pixel_world()), 1.5, kContact);
    }
  }
}

Renderer::Renderer(const std::string& resource_root) : impl_(std::make_unique<Impl>()) {
  const fs::path shaders = fs::path(resource_root) / "shaders";
  impl_->particle_program =
      load_program((shaders / "particles.vert").string(), (shaders / "particles.frag").string());
  impl_->solid_program = load_program((shaders / "solid.vert").string(), (shaders / "solid.frag").string());
  const GLuint p = impl_->particle_program;
  impl_->p_projection = glGetUniformLocation(p, "u_projection");
  impl_->p_radius = glGetUniformLocation(p, "u_radius");
  impl_->p_pixel_world = glGetUniformLocation(p, "u_pixel_world");
  impl_->p_range = glGetUniformLocation(p, "u_range");
  impl_->p_colormap = glGetUniformLocation(p, "u_colormap");
  impl_->p_solid = glGetUniformLocation(p, "u_solid_color");
  impl_->p_ring = glGetUniformLocation(p, "u_ring");
  impl_->dense_program =
      load_program((shaders / "particles_dense.vert").string(), (shaders / "particles_dense.frag").string());
  const GLuint d = impl_->dense_program;
  impl_->d_projection = glGetUniformLocation(d, "u_projection");
  impl_->d_point_pixels = glGetUniformLocation(d, "u_point_pixels");
  impl_->d_range = glGetUniformLocation(d, "u_range");
  impl_->d_colormap = glGetUniformLocation(d, "u_colormap");
  impl_->s_projection = glGetUniformLocation(impl_->solid_program, "u_projection");
  impl_->load_colormaps(resource_root);
  impl_->make_buffers();
  check_gl("Renderer set-up");
}

Renderer::~Renderer() {
  // the context that created the objects must be current; deleting in another one is harmless
  glDeleteProgram(impl_->particle_program);
  glDeleteProgram(impl_->dense_program);
  glDeleteProgram(impl_->solid_program);
  for (GLuint b : {impl_->particle_vbo, impl_->attached_vbo, impl_->solid_vbo}) glDeleteBuffers(1, &b);
  for (GLuint a : {impl_->particle_vao, impl_->attached_vao, impl_->solid_vao}) glDeleteVertexArrays(1, &a);
  for (auto& [name, cm] : impl_->colormaps) glDeleteTextures(1, &cm.texture);
}

void Renderer::draw(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings, int width,
                    int height) {
  Impl& m = *impl_;
  m.colormap(settings.colormap);  // unknown names fail before anything is drawn
  m.last_colormap = settings.colormap;
  m.update_range(snapshot, settings);
  m.record_trails(snapshot, settings.trail_length);
  m.update_deformation(snapshot, settings);

  // fixed state for the whole picture: 2D, no depth, straight alpha blending
  glViewport(0, 0, width, height);
  glClearColor(settings.background[0], settings.background[1], settings.background[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  use_flat_blending();

  float projection[16];
  camera.projection(height > 0 ? double(width) / height : 1.0, projection);
  const double pixel_world = camera.view_height / std::max(height, 1);
  m.pixel_world = pixel_world;
  m.mesh.set_pixel_world(pixel_world);

  // back to front: rigid bodies, particles, then everything drawn over them
  if (settings.show_bodies) m.build_bodies(snapshot, false);
  m.draw_mesh(projection);
  m.draw_particles(snapshot, settings, projection, pixel_world);
  m.build_overlay_geometry(snapshot, settings);
  m.draw_mesh(projection);
  glBindVertexArray(0);
  glUseProgram(0);
}

namespace {

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

float Renderer::last_range_min() const { return impl_->range_min; }
float Renderer::last_range_max() const { return impl_->range_max; }
double Renderer::last_deform() const { return impl_->deform_used; }
const std::vector<float>& Renderer::drawn_x() const { return impl_->shown_x; }
const std::vector<float>& Renderer::drawn_y() const { return impl_->shown_y; }

std::vector<std::string> Renderer::colormap_names() const {
  std::vector<std::string> names;
  for (const auto& [name, cm] : impl_->colormaps) names.push_back(name);
  return names;
}

const std::vector<unsigned char>& Renderer::colormap_table(const std::string& name) const {
  return impl_->colormap(name).table;
}

void Renderer::clear_trails() {
  impl_->trails.clear();
  impl_->trail_time = -1e300;
}

}  // namespace periflex
