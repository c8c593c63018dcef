// What is drawn over the bodies and particles: bonds of small bodies, virtual bodies, springs,
// trails, joint and driver markers, probes and active contacts.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cstdint>

namespace periflex {

namespace {
using render_parts::kAttachment;
using render_parts::kBond;
using render_parts::kContact;
using render_parts::kDriver;
using render_parts::kJoint;
using render_parts::kJointHole;
using render_parts::kProbe;
using render_parts::kSlider;
using render_parts::kSpring;
using render_parts::kTrail;
}  // namespace

void Renderer::Impl::build_overlay_geometry(const Snapshot& s, const RenderSettings& settings) {
  // bonds: thin translucent lines between the particles of small bodies
  if (settings.show_bonds) {
    const size_t n = std::min(shown_x.size(), shown_y.size());
    for (const auto& [i, j] : s.bond_pairs) {
      if (i < 0 || j < 0 || size_t(i) >= n || size_t(j) >= n) continue;
      mesh.line(Vec2(shown_x[i], shown_y[i]), Vec2(shown_x[j], shown_y[j]), 1.0, kBond);
    }
  }
  if (settings.show_bodies) build_bodies(s, true);
  if (settings.show_springs) {
    for (const auto& sp : s.springs) {
      const double len = (sp.b - sp.a).norm();
      const double amplitude = std::min(0.08 * len, 8.0 * mesh.pixel_world());
      mesh.zigzag(sp.a, sp.b, 10, amplitude, 1.5, kSpring);
    }
  }
  // trails fade from transparent (old) to opaque (new)
  if (settings.show_trails) {
    for (const auto& t : trails.lines()) {
      const size_t m = t.size();
      for (size_t i = 1; i < m; ++i) {
        Rgba8 c = kTrail;
        c.a = static_cast<uint8_t>(40 + 215 * i / m);
        mesh.line(t[i - 1], t[i], 1.5, c);
      }
    }
  }
  if (settings.show_markers) {
    using Kind = Snapshot::Marker::Kind;
    for (const auto& marker : s.markers) {
      // markers on a virtual body move with it
      // (a joint drawn at one point, between a virtual body and another, is drawn on the virtual one)
      Snapshot::Marker m = marker;
      const auto moves = [&](int b) { return b > 0 && static_cast<size_t>(b) < body_shift.size() && body_shift[b].moves; };
      const bool one_point = m.kind == Kind::kRevolute || m.kind == Kind::kRigid;
      m.a = !one_point || moves(marker.body_a) || !moves(marker.body_b) ? shown_point(marker.body_a, marker.a)
                                                                        : shown_point(marker.body_b, marker.b);
      m.b = shown_point(marker.body_b, marker.b);
      switch (m.kind) {
        case Kind::kRevolute:
          mesh.disc_px(m.a, 4.5, kJoint);
          mesh.disc_px(m.a, 2.0, kJointHole);
          break;
        case Kind::kTranslational:
          mesh.dashed_polyline({m.a, m.b}, false, 1.5, 5.0, 3.0, kSlider);
          mesh.square_px(m.a, 3.5, kSlider);
          break;
        case Kind::kRigid:
          mesh.square_px(m.a, 3.5, kJoint);
          break;
        case Kind::kLink:
          mesh.line(m.a, m.b, 2.0, kJoint);
          mesh.ring_px(m.a, 4.0, 1.5, kJoint);
          mesh.ring_px(m.b, 4.0, 1.5, kJoint);
          break;
        case Kind::kDriver:
          mesh.ring_px(m.a, 7.0, 2.0, kDriver);
          mesh.disc_px(m.a, 2.5, kDriver);
          break;
        case Kind::kAttachment:
          mesh.square_px(m.a, 5.0, kAttachment, true);
          break;
      }
    }
  }
  // probes on what carries them: a particle's magnified place, a virtual body's shifted one
  if (settings.show_probes)
    for (const auto& p : s.probes)
      mesh.cross_px(deform_used == 1.0 ? p.position : magnified_probe(p, shown_x, shown_y, body_shift), 4.0, 1.5,
                    kProbe);
  // active contacts: a dot where each acts and a stroke along its force, 6 to 24 px long by its
  // share of the largest force
  if (settings.show_contacts && !s.contacts.empty()) {
    double largest = 0.0;
    for (const auto& c : s.contacts) largest = std::max(largest, c.force.norm());
    for (const auto& c : s.contacts) {
      const double f = c.force.norm();
      mesh.disc_px(c.point, 2.5, kContact);
      if (f > 0.0 && largest > 0.0)
        mesh.line(c.point, c.point + c.force / f * ((6.0 + 18.0 * f / largest) * mesh.pixel_world()), 1.5, kContact);
    }
  }
}

}  // namespace periflex
