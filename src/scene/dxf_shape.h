// A specimen drawn in CAD: the outlines of an ASCII DXF file. Lines, arcs, circles and (light)
// polylines, bulges included, are joined end to end into closed loops; a loop inside no other
// is material, a loop inside one is a hole. Arcs become polygons of kDxfSegmentsPerTurn sides
// per full turn. Entities of other types (text, dimensions, hatches) are ignored.
//
// Read here rather than through a DXF library: Debian's dxflib is a static library built
// without position-independent code, which the Python module (a shared object holding the
// scene reader) cannot link.
#pragma once

#include <string>
#include <vector>

#include "core/vec2.h"

namespace periflex {

struct DxfShapeOptions {
  std::string layer;          // only this layer's entities; empty: every layer
  double scale = 1.0;         // metres per drawing unit
  double tolerance = -1.0;    // largest gap closed between entity ends (drawing units); < 0: 1e-6 of the drawing's size
};

struct DxfOutline {
  std::vector<std::vector<Vec2>> material;  // outer loops, counter-clockwise, in metres
  std::vector<std::vector<Vec2>> holes;     // loops inside an outer loop, counter-clockwise
};

// Polygon sides per full turn of an arc or circle: the chord's deviation is 7.5e-5 of the radius.
constexpr int kDxfSegmentsPerTurn = 256;
// Largest DXF file read (bytes).
constexpr double kMaxDxfBytes = 64e6;

// Reads the outlines. Throws InputError naming the file (and line): unreadable, not a DXF, no
// closed loop on the layer, an entity whose end meets no other (its type, line and the gap's
// position), a loop inside a hole.
DxfOutline read_dxf_shape(const std::string& path, const DxfShapeOptions& options);

}  // namespace periflex
