// What is under the mouse: a rigid body (by its shapes) or a particle, and the mouse spring
// that grabs it. No GL.
#pragma once

#include <optional>
#include <vector>

#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {

// The spring that grabs what lies at `world` in `snapshot`: a rigid body whose shape contains
// the point (its body-fixed grab point), else the nearest particle within one grid spacing
// (or within `tolerance`, when larger). Ground and virtual bodies are not grabbed.
// Empty when nothing is there.
std::optional<MouseSpring> pick(const Snapshot& snapshot, const Vec2& world, double tolerance);

// The particle nearest to `world` among positions x, y (the snapshot's, or where the renderer
// drew them magnified), within one grid spacing of its body (or `tolerance`, when larger);
// -1 when none is.
int particle_at(const Snapshot& snapshot, const std::vector<float>& x, const std::vector<float>& y,
                const Vec2& world, double tolerance);

}  // namespace periflex
