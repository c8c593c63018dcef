#include "render/view.h"

#include <algorithm>

#include "render/solid_mesh.h"

namespace periflex {

void Bounds::add(const Vec2& p) {
  if (empty()) {
    lo = hi = p;  // first point
    return;
  }
  lo = lo.cwiseMin(p);
  hi = hi.cwiseMax(p);
}

void Bounds::add(const Bounds& b) {
  if (b.empty()) return;
  if (empty()) {
    *this = b;
    return;
  }
  lo = lo.cwiseMin(b.lo);
  hi = hi.cwiseMax(b.hi);
}

bool Bounds::contains(const Bounds& other) const {
  if (other.empty()) return true;
  if (empty()) return false;
  return other.lo.x() >= lo.x() && other.lo.y() >= lo.y() && other.hi.x() <= hi.x() && other.hi.y() <= hi.y();
}

Bounds particle_bounds(const Snapshot& s) {
  Bounds b;
  const size_t n = std::min(s.px.size(), s.py.size());
  if (n == 0) return b;
  // plain min/max over floats; the loop vectorises
  float x0 = s.px[0], x1 = s.px[0], y0 = s.py[0], y1 = s.py[0];
  for (size_t i = 1; i < n; ++i) {
    x0 = std::min(x0, s.px[i]);
    x1 = std::max(x1, s.px[i]);
    y0 = std::min(y0, s.py[i]);
    y1 = std::max(y1, s.py[i]);
  }
  b.lo = Vec2(x0, y0);
  b.hi = Vec2(x1, y1);
  return b;
}

Bounds snapshot_bounds(const Snapshot& s) {
  Bounds b = particle_bounds(s);
  if (s.geometry) {
    const size_t nb = std::min(s.geometry->bodies.size(), s.bodies.size());
    for (size_t k = 0; k < nb; ++k) {
      const Snapshot::Pose& pose = s.bodies[k];
      for (const ShapeDef& shape : s.geometry->bodies[k].shapes)
        for (const Vec2& p : shape_outline(shape, Vec2(pose.x, pose.y), pose.angle, 16)) b.add(p);
    }
  }
  for (const auto& m : s.markers) {
    b.add(m.a);
    if (m.kind == Snapshot::Marker::Kind::kLink || m.kind == Snapshot::Marker::Kind::kTranslational) b.add(m.b);
  }
  for (const auto& sp : s.springs) {
    b.add(sp.a);
    b.add(sp.b);
  }
  for (const auto& p : s.probes) b.add(p.position);
  return b;
}

Bounds scene_bounds(const Snapshot& s) {
  if (s.geometry && (s.geometry->bounds_max - s.geometry->bounds_min).minCoeff() > 0.0) {
    Bounds b;
    b.lo = s.geometry->bounds_min;
    b.hi = s.geometry->bounds_max;
    return b;
  }
  return snapshot_bounds(s);
}

Camera fit_camera(const Snapshot& snapshot, int width, int height, double margin) {
  Camera camera;
  const Bounds b = scene_bounds(snapshot);
  const double aspect = height > 0 ? double(width) / height : 1.0;
  if (b.empty())
    camera.fit(Vec2(-1, -1), Vec2(1, 1), aspect, margin);
  else
    camera.fit(b.lo, b.hi, aspect, margin);
  return camera;
}

void widen_to_show(Camera& camera, const Snapshot& snapshot, int width, int height) {
  const Bounds now = snapshot_bounds(snapshot);
  const double aspect = double(width) / height;
  const Vec2 half(0.5 * camera.view_height * aspect, 0.5 * camera.view_height);
  Bounds view;
  view.add(camera.center - half);
  view.add(camera.center + half);
  if (!now.empty() && !view.contains(now)) camera.fit(now.lo, now.hi, aspect);
}

}  // namespace periflex
