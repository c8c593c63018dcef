#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace periflex {

void Camera::fit(const Vec2& lo, const Vec2& hi, double aspect, double margin) {
  // an empty or degenerate box keeps a unit view around its centre
  const double w = std::max(hi.x() - lo.x(), 0.0);
  const double h = std::max(hi.y() - lo.y(), 0.0);
  center = 0.5 * (lo + hi);
  const double a = aspect > 0.0 ? aspect : 1.0;
  const double needed = std::max(h, w / a) * (1.0 + 2.0 * margin);
  view_height = needed > 0.0 ? needed : 1.0;
}

void Camera::pan_pixels(double dx_px, double dy_px, int height_px) {
  // the world follows the cursor: dragging right moves the centre left; pixel y points down
  const double world_per_px = view_height / std::max(height_px, 1);
  center.x() -= dx_px * world_per_px;
  center.y() += dy_px * world_per_px;
}

void Camera::zoom_at(double factor, double cursor_x_px, double cursor_y_px, int width_px, int height_px) {
  if (!(factor > 0.0)) return;
  // remember the world point under the cursor, scale, then move the centre so it stays there
  const Vec2 anchor = to_world(cursor_x_px, cursor_y_px, width_px, height_px);
  view_height /= factor;
  const double s = view_height / std::max(height_px, 1);
  center = anchor - Vec2((cursor_x_px - 0.5 * width_px) * s, (0.5 * height_px - cursor_y_px) * s);
}

Vec2 Camera::to_world(double x_px, double y_px, int width_px, int height_px) const {
  const double s = view_height / std::max(height_px, 1);
  return center + Vec2((x_px - 0.5 * width_px) * s, (0.5 * height_px - y_px) * s);
}

Vec2 Camera::to_pixels(const Vec2& world, int width_px, int height_px) const {
  const double s = std::max(height_px, 1) / view_height;
  return Vec2(0.5 * width_px + (world.x() - center.x()) * s, 0.5 * height_px - (world.y() - center.y()) * s);
}

void Camera::projection(double aspect, float out[16]) const {
  // maps [cx - w/2, cx + w/2] x [cy - h/2, cy + h/2] to normalised device coordinates
  const double half_h = 0.5 * view_height;
  const double half_w = half_h * (aspect > 0.0 ? aspect : 1.0);
  std::fill(out, out + 16, 0.0f);
  out[0] = static_cast<float>(1.0 / half_w);
  out[5] = static_cast<float>(1.0 / half_h);
  out[10] = -1.0f;
  out[12] = static_cast<float>(-center.x() / half_w);
  out[13] = static_cast<float>(-center.y() / half_h);
  out[15] = 1.0f;
}

}  // namespace periflex
