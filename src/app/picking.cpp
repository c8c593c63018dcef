#include "app/picking.h"

#include <algorithm>
#include <cmath>

namespace periflex {

std::optional<MouseSpring> pick(const Snapshot& snapshot, const Vec2& world, double tolerance) {
  if (!snapshot.geometry) return std::nullopt;
  const SceneGeometry& g = *snapshot.geometry;

  // rigid bodies first, last drawn (topmost) first; body-fixed point = A^T (p - r)
  const size_t bodies = std::min(g.bodies.size(), snapshot.bodies.size());
  for (size_t b = bodies; b-- > 1;) {
    if (g.bodies[b].ground || g.bodies[b].is_virtual) continue;
    const Snapshot::Pose& pose = snapshot.bodies[b];
    const Vec2 local = rotation(pose.angle).transpose() * (world - Vec2(pose.x, pose.y));
    for (const ShapeDef& shape : g.bodies[b].shapes) {
      if (!shape.contains(local)) continue;
      MouseSpring spring;
      spring.body = static_cast<int>(b) - 1;  // rigid body index: geometry index minus the ground
      spring.local_point = local;
      spring.target = world;
      return spring;
    }
  }

  // then the nearest particle within reach
  const int best = particle_at(snapshot, snapshot.px, snapshot.py, world, tolerance);
  if (best < 0) return std::nullopt;
  MouseSpring spring;
  spring.particle = best;
  spring.target = world;
  return spring;
}

int particle_at(const Snapshot& snapshot, const std::vector<float>& x, const std::vector<float>& y,
                const Vec2& world, double tolerance) {
  if (!snapshot.geometry) return -1;
  int best = -1;
  double best_d2 = 0.0;
  const int n = static_cast<int>(std::min(x.size(), y.size()));
  for (const SceneGeometry::FlexBody& fb : snapshot.geometry->flex_bodies) {
    const double reach = std::max(fb.grid_spacing, tolerance);
    const int end = std::min<int>(fb.first_particle + fb.particle_count, n);
    for (int i = fb.first_particle; i < end; ++i) {
      const double dx = x[i] - world.x(), dy = y[i] - world.y();
      const double d2 = dx * dx + dy * dy;
      if (d2 <= reach * reach && (best < 0 || d2 < best_d2)) {
        best = i;
        best_d2 = d2;
      }
    }
  }
  return best;
}

}  // namespace periflex
