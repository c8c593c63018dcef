// The outline of a shape as a closed polygon: what the renderer fills and what the VTK writer
// stores for a rigid body. Geometry only, no drawing.
#pragma once

#include <vector>

#include "core/vec2.h"
#include "scene/scene_def.h"

namespace periflex {

// Outline of a body-fixed shape placed at a pose (x, y, angle), as a closed polygon in world
// coordinates: boxes as 4 corners, circles and bar caps as `segments`-gons.
std::vector<Vec2> shape_outline(const ShapeDef& shape, const Vec2& position, double angle, int segments = 48);

}  // namespace periflex
