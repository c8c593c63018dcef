#version 330 core
// One point per particle, sized to the disc: a single vertex per particle keeps the software
// rasteriser's vertex work to a minimum for hundreds of thousands of particles.
layout(location = 1) in vec3 a_particle;  // world x, world y, field value

uniform mat4 u_projection;
uniform float u_radius;       // disc radius, world units
uniform float u_pixel_world;  // world size of one pixel
uniform vec2 u_range;         // field value mapped to the two ends of the colour map

out float v_t;                // colour map coordinate
flat out float v_aa;          // one pixel, in disc radii
flat out float v_pad;         // point half-size, in disc radii

void main() {
  // never thinner than about a pixel, so dense bodies do not vanish when zoomed out
  float r = max(u_radius, 0.6 * u_pixel_world);
  // grow the point by a pixel so the anti-aliased edge is not clipped
  v_pad = 1.0 + u_pixel_world / r;
  v_aa = u_pixel_world / r;
  float span = u_range.y - u_range.x;
  v_t = clamp((a_particle.z - u_range.x) / (span > 0.0 ? span : 1.0), 0.0, 1.0);
  gl_Position = u_projection * vec4(a_particle.xy, 0.0, 1.0);
  gl_PointSize = 2.0 * r * v_pad / u_pixel_world;
}
