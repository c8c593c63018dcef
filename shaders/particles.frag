#version 330 core
// A disc from the distance to the point's centre, its edge smoothed over one pixel.
in float v_t;
flat in float v_aa;
flat in float v_pad;

uniform sampler2D u_colormap;  // 256 x 1 colour map
uniform vec4 u_solid_color;    // alpha > 0: draw in this colour instead of the map
uniform float u_ring;          // > 0: draw only a ring of this width (in radii) at the edge

out vec4 frag_color;

void main() {
  float d = length(gl_PointCoord * 2.0 - 1.0) * v_pad;
  float alpha = 1.0 - smoothstep(1.0 - 0.5 * v_aa, 1.0 + 0.5 * v_aa, d);
  if (u_ring > 0.0) alpha *= smoothstep(1.0 - u_ring - 0.5 * v_aa, 1.0 - u_ring + 0.5 * v_aa, d);
  if (alpha <= 0.003) discard;
  vec4 color = u_solid_color.a > 0.0 ? u_solid_color : texture(u_colormap, vec2(v_t, 0.5));
  frag_color = vec4(color.rgb, color.a * alpha);
}
