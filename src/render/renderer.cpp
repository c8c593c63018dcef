// The renderer: its set-up (shaders, colour maps, buffers), the colour range and the deformation
// of each frame, and the frame drawn back to front through its passes (body_pass, particle_pass,
// marker_pass, overlay_pass .cpp, sharing renderer_impl.h); trails in trails.cpp.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "io/image.h"
#include "render/renderer_impl.h"

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
using render_parts::field_values;
using render_parts::use_flat_blending;
}  // namespace

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
  m.trails.record(snapshot, settings.trail_length);
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

void Renderer::clear_trails() { impl_->trails.clear(); }

}  // namespace periflex
