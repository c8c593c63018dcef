// Shapes made of other shapes: `union`, `difference` (the first minus the others) and
// `intersection`, so that a plate minus holes minus a notch is one shape, and a no-fail zone or
// a load region can be as intricate as the body. Exact on the grid: a cell is inside exactly
// when the inside tests of the operands combine to say so, and the grid scan combines the
// operands' runs of cells the same way (scene/grid_scan.cpp).
//
//   shape = { type = "difference", shapes = [ { type = "box", width = 0.08, height = 0.04 },
//                                             { type = "circle", radius = 0.006 } ] }
#pragma once

#include <string>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

class TableReader;

// Inside test of a kBoolean shape.
bool boolean_contains(const ShapeDef& shape, const Vec2& p);

// An area no smaller than the shape's (union: the sum; difference: the first operand's;
// intersection: the smallest operand's), for the particle estimates made before filling.
double boolean_area_bound(const ShapeDef& shape);

// Axis-aligned bounds (union: of all operands; difference: of the first; intersection: the
// overlap of the operands' bounds, possibly empty: lo > hi).
void boolean_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi);

// Reads `shapes` of a table whose type is "union", "difference" or "intersection"; each operand
// may be any of `allowed`. At least two operands (one for a union).
ShapeDef read_boolean_shape(TableReader& in, const std::string& type, const std::vector<ShapeDef::Kind>& allowed);

}  // namespace periflex
