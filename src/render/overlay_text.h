// Overlay text without a font texture or a UI library: stb_easy_font builds each glyph from
// axis-aligned quads, which go into a SolidMesh as triangles in pixel coordinates (x right, y
// down). Any thread may lay out text at the same time; nothing here is global.
#pragma once

#include <string>

#include "render/solid_mesh.h"

namespace periflex {

// Whole-pixel magnification of the 1-pixel-stroke font: text stays crisp at any whole scale.
// One line of text at scale 1 is about 7 pixels from cap to baseline.
int overlay_text_scale(int width, int height);
// Width in pixels of one line of text at `scale`.
int text_width_px(const std::string& text, int scale);
// Height in pixels of one line of text at `scale` (capitals and descenders).
int text_height_px(int scale);
// Appends the glyphs of one line with their top-left corner at (x, y), in pixels.
void append_text(SolidMesh& mesh, double x, double y, const std::string& text, int scale, Rgba8 color);

}  // namespace periflex
