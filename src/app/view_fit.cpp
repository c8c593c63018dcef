#include "app/view_fit.h"

#include <algorithm>

#include "render/view.h"

namespace periflex {

Camera fit_camera_beside_panels(const Snapshot& snapshot, int width, int height, int left_inset) {
  // bounds: the initial configuration, grown by where the particles are now
  Bounds box = scene_bounds(snapshot);
  box.add(particle_bounds(snapshot));
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

}  // namespace periflex
