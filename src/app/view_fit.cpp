#include "app/view_fit.h"

#include <algorithm>

namespace periflex {

namespace {

// everything drawn now: shapes at their poses, particles, markers, springs, probes
Bounds drawn_bounds(const Snapshot& snapshot) {
  Bounds box = snapshot_bounds(snapshot);
  box.add(particle_bounds(snapshot));
  return box;
}

}  // namespace

Bounds framing_bounds(const Snapshot& snapshot) {
  Bounds box = scene_bounds(snapshot);
  box.add(drawn_bounds(snapshot));
  return box;
}

Camera fit_camera_beside_panels(const Bounds& bounds, int width, int height, int left_inset) {
  Bounds box = bounds;
  if (box.empty()) box.add(Vec2::Zero());
  // a point or a line still needs a visible box
  const double extent = std::max({box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y(), 1e-6});
  for (int axis = 0; axis < 2; ++axis) {
    if (box.hi[axis] - box.lo[axis] < 0.05 * extent) {
      box.lo[axis] -= 0.05 * extent;
      box.hi[axis] += 0.05 * extent;
    }
  }

  // fit in the free part of the window, then shift the centre so that part is centred
  const int inset = std::clamp(left_inset, 0, std::max(0, width - 64));
  const int free_width = std::max(1, width - inset);
  Camera camera;
  camera.fit(box.lo, box.hi, double(free_width) / std::max(1, height));
  const double world_per_pixel = camera.view_height / std::max(1, height);
  camera.center.x() -= 0.5 * inset * world_per_pixel;
  return camera;
}

Camera fit_camera_beside_panels(const Snapshot& snapshot, int width, int height, int left_inset) {
  return fit_camera_beside_panels(framing_bounds(snapshot), width, height, left_inset);
}

Framing start_framing(const Snapshot& snapshot) {
  Framing f;
  f.seen = framing_bounds(snapshot);
  f.shown = f.seen;
  return f;
}

bool grow_framing(Framing& framing, const Snapshot& snapshot, double margin) {
  const Bounds now = drawn_bounds(snapshot);
  if (now.empty()) return false;
  framing.seen.add(now);
  if (framing.shown.contains(now)) return false;
  // room to move before the next growth, measured on what was seen (so margins never compound)
  const Vec2 pad = margin * (framing.seen.hi - framing.seen.lo);
  framing.shown = framing.seen;
  framing.shown.lo -= pad;
  framing.shown.hi += pad;
  return true;
}

Camera picture_camera(const Camera& window_camera, int height, int left_inset) {
  Camera camera = window_camera;
  camera.center.x() += 0.5 * left_inset * camera.view_height / std::max(1, height);
  return camera;
}

}  // namespace periflex
