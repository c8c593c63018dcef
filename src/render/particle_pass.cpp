// The particle pass: one disc per particle coloured by the field through the colour map (opaque
// squares where discs are under a few pixels), and rings around particles held by rigid bodies.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cmath>

namespace periflex {

namespace {
using render_parts::field_values;
using render_parts::kAttachedRing;
using render_parts::kDenseDiscPixels;
}  // namespace

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

}  // namespace periflex
