#version 330 core
// Particles whose discs are under a few pixels across: one opaque square point each, its
// colour looked up here so the fragment stage only copies it. At this size a smoothed disc
// edge only blurs neighbours into each other and triples the fragments the software
// rasteriser has to shade.
layout(location = 1) in vec3 a_particle;  // world x, world y, field value

uniform mat4 u_projection;
uniform float u_point_pixels;  // square side, pixels
uniform vec2 u_range;          // field value mapped to the two ends of the colour map
uniform sampler2D u_colormap;  // 256 x 1 colour map

flat out vec3 v_color;

void main() {
  float span = u_range.y - u_range.x;
  float t = clamp((a_particle.z - u_range.x) / (span > 0.0 ? span : 1.0), 0.0, 1.0);
  v_color = textureLod(u_colormap, vec2(t, 0.5), 0.0).rgb;
  gl_Position = u_projection * vec4(a_particle.xy, 0.0, 1.0);
  gl_PointSize = u_point_pixels;
}
