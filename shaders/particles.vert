#version 330 core
// One instance per particle: a screen-aligned quad around the particle's centre.
layout(location = 0) in vec2 a_corner;    // quad corner in [-1, 1]^2
layout(location = 1) in vec3 a_instance;  // world x, world y, field value

uniform mat4 u_projection;
uniform float u_radius;       // disc radius, world units
uniform float u_pixel_world;  // world size of one pixel
uniform vec2 u_range;         // field value mapped to the two ends of the colour map

out vec2 v_local;             // position in the quad, in disc radii
out float v_t;                // colour map coordinate
flat out float v_aa;          // one pixel, in disc radii

void main() {
  // never thinner than about a pixel, so dense bodies do not vanish when zoomed out
  float r = max(u_radius, 0.6 * u_pixel_world);
  // grow the quad by a pixel so the anti-aliased edge is not clipped
  float pad = 1.0 + u_pixel_world / r;
  v_local = a_corner * pad;
  v_aa = u_pixel_world / r;
  float span = u_range.y - u_range.x;
  v_t = clamp((a_instance.z - u_range.x) / (span > 0.0 ? span : 1.0), 0.0, 1.0);
  gl_Position = u_projection * vec4(a_instance.xy + v_local * r, 0.0, 1.0);
}
