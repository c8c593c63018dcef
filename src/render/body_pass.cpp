// The rigid-body pass: each body's shapes filled and outlined where the drawing shows the body
// (moved with its magnified particles when it is virtual), the ground in its own colours.
#include "render/renderer_impl.h"

#include <iterator>
#include <vector>

#include "scene/shape_outline.h"

namespace periflex {

namespace {
using render_parts::kBodyEdge;
using render_parts::kBodyFills;
using render_parts::kGroundEdge;
using render_parts::kGroundFill;
using render_parts::kVirtualEdge;
using render_parts::kVirtualFill;
}  // namespace

// a point carried by geometry body `body`, where the drawing shows it
Vec2 Renderer::Impl::shown_point(int body, const Vec2& p) const {
  return body > 0 && static_cast<size_t>(body) < body_shift.size() ? body_shift[body].apply(p) : p;
}

void Renderer::Impl::build_bodies(const Snapshot& s, bool virtual_bodies) {
  if (!s.geometry) return;
  const size_t nb = std::min(s.geometry->bodies.size(), s.bodies.size());
  for (size_t k = 0; k < nb; ++k) {
    const SceneGeometry::Body& body = s.geometry->bodies[k];
    if (body.is_virtual != virtual_bodies) continue;
    const Snapshot::Pose& pose = s.bodies[k];
    // a virtual body moves with its magnified particles (identity otherwise)
    const Vec2 position = shown_point(static_cast<int>(k), Vec2(pose.x, pose.y));
    const double angle = pose.angle + (k < body_shift.size() ? body_shift[k].angle : 0.0);
    for (const ShapeDef& shape : body.shapes) {
      const std::vector<Vec2> outline = shape_outline(shape, position, angle);
      if (outline.size() < 2) continue;
      if (body.is_virtual) {
        // virtual bodies: see-through fill, dashed edge
        mesh.fill_polygon(outline, kVirtualFill);
        mesh.dashed_polyline(outline, true, 1.5, 6.0, 4.0, kVirtualEdge);
      } else if (body.ground) {
        mesh.fill_polygon(outline, kGroundFill);
        mesh.polyline(outline, true, 1.5, kGroundEdge);
      } else {
        mesh.fill_polygon(outline, kBodyFills[k % std::size(kBodyFills)]);
        mesh.polyline(outline, true, 1.5, kBodyEdge);
      }
      // a radius line shows how circles turn
      if (shape.kind == ShapeDef::Kind::kCircle && !body.ground)
        mesh.line(position + rotation(angle) * shape.center,
                  position + rotation(angle) * (shape.center + Vec2(shape.radius, 0.0)), 1.5,
                  body.is_virtual ? kVirtualEdge : kBodyEdge);
    }
  }
}

}  // namespace periflex
