#include "render/overlay_text.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace periflex {

namespace {

// stb_easy_font knows printable ASCII only (it indexes its tables by code - 32): anything else
// is shown as '?', so a scene name in UTF-8 cannot read outside them.
std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

// Quads stb_easy_font emits for the text, read from its own segment tables, so the vertex
// buffer is never too short (it drops glyphs silently when it is).
int quad_count(const std::string& text) {
  int quads = 0;
  for (const char c : text) {
    const int k = c - 32;
    quads += stb_easy_font_charinfo[k + 1].h_seg - stb_easy_font_charinfo[k].h_seg;
    quads += stb_easy_font_charinfo[k + 1].v_seg - stb_easy_font_charinfo[k].v_seg;
  }
  return quads;
}

// One vertex as stb_easy_font writes it: position, an unused depth, an RGBA colour.
struct FontVertex {
  float x, y, z;
  unsigned char rgba[4];
};
static_assert(sizeof(FontVertex) == 16);

}  // namespace

int overlay_text_scale(int width, int height) {
  // about 1.5% of the smaller side per line: 1 up to 720p, 2 for full HD, 3 for 4K
  return std::clamp(std::min(width, height) / 720 + 1, 1, 4);
}

int text_width_px(const std::string& text, int scale) {
  std::string t = printable(text);
  return stb_easy_font_width(t.data()) * scale;
}

int text_height_px(int scale) { return 9 * scale; }

void append_text(SolidMesh& mesh, double x, double y, const std::string& text, int scale, Rgba8 color) {
  std::string t = printable(text);
  if (t.empty()) return;
  std::vector<FontVertex> quads(4 * static_cast<size_t>(quad_count(t)));
  if (quads.empty()) return;  // only spaces
  const int emitted = stb_easy_font_print(0.0f, 0.0f, t.data(), nullptr, quads.data(),
                                          static_cast<int>(quads.size() * sizeof(FontVertex)));
  // each quad (corners in order around it) as two triangles, magnified about the origin
  const double s = scale;
  for (int q = 0; q < emitted; ++q) {
    Vec2 corner[4];
    for (int j = 0; j < 4; ++j) corner[j] = Vec2(x + s * quads[4 * q + j].x, y + s * quads[4 * q + j].y);
    mesh.triangle(corner[0], corner[1], corner[2], color);
    mesh.triangle(corner[0], corner[2], corner[3], color);
  }
}

}  // namespace periflex
