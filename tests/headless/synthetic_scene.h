// A hand-built snapshot that exercises everything the renderer draws: a cracked plate of
// particles with a damage pattern, a small body with bonds, rigid shapes of every kind, a virtual
// body, every marker kind, a spring and a probe. It does not depend on the solver.
#pragma once

#include <cmath>
#include <memory>

#include "solve/snapshot.h"

namespace periflex::testing {

inline ShapeDef make_box(Vec2 center, double w, double h, double angle = 0.0) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBox;
  s.center = center;
  s.width = w;
  s.height = h;
  s.angle = angle;
  return s;
}

inline ShapeDef make_circle(Vec2 center, double r) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kCircle;
  s.center = center;
  s.radius = r;
  return s;
}

// Plate: nx x ny particles of spacing h with lower-left corner at origin; a horizontal crack from
// the left edge to crack_tip_x along y = crack_y shows as a band of damage.
inline Snapshot make_synthetic_snapshot(bool with_particles = true) {
  auto g = std::make_shared<SceneGeometry>();
  g->scene_name = "synthetic test scene";
  Snapshot s;
  s.time = 0.0125;
  s.step = 1250;

  // rigid bodies: ground (floor), a crank box, a wheel, a concave polygon, a bar, a virtual body
  SceneGeometry::Body ground;
  ground.name = "ground";
  ground.ground = true;
  ground.shapes.push_back(make_box(Vec2(0.3, -0.06), 1.0, 0.04));
  g->bodies.push_back(ground);
  s.bodies.push_back({0.0, 0.0, 0.0});

  SceneGeometry::Body crank;
  crank.name = "crank";
  crank.shapes.push_back(make_box(Vec2(0.0, 0.0), 0.16, 0.03));
  g->bodies.push_back(crank);
  s.bodies.push_back({0.75, 0.12, 0.6});

  SceneGeometry::Body wheel;
  wheel.name = "wheel";
  wheel.shapes.push_back(make_circle(Vec2(0.0, 0.0), 0.06));
  g->bodies.push_back(wheel);
  s.bodies.push_back({0.72, 0.32, 0.3});

  SceneGeometry::Body ell;
  ell.name = "bracket";
  ShapeDef poly;
  poly.kind = ShapeDef::Kind::kPolygon;
  poly.vertices = {Vec2(0, 0), Vec2(0.1, 0), Vec2(0.1, 0.03), Vec2(0.03, 0.03), Vec2(0.03, 0.1), Vec2(0, 0.1)};
  ell.shapes.push_back(poly);
  g->bodies.push_back(ell);
  s.bodies.push_back({-0.2, 0.15, -0.2});

  SceneGeometry::Body bar;
  bar.name = "rod";
  ShapeDef b;
  b.kind = ShapeDef::Kind::kBar;
  b.p1 = Vec2(-0.1, 0.0);
  b.p2 = Vec2(0.1, 0.0);
  b.radius = 0.01;
  bar.shapes.push_back(b);
  g->bodies.push_back(bar);
  s.bodies.push_back({-0.12, 0.36, 0.4});

  SceneGeometry::Body grip;
  grip.name = "grip";
  grip.is_virtual = true;
  grip.shapes.push_back(make_box(Vec2(0.0, 0.0), 0.05, 0.32));
  g->bodies.push_back(grip);
  s.bodies.push_back({0.01, 0.15, 0.0});

  if (with_particles) {
    // the plate
    const int nx = 60, ny = 30;
    const double h = 0.01;
    SceneGeometry::FlexBody plate;
    plate.name = "plate";
    plate.first_particle = 0;
    plate.particle_count = nx * ny;
    plate.grid_spacing = h;
    g->flex_bodies.push_back(plate);
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double x = (i + 0.5) * h, y = (j + 0.5) * h;
        const double crack_y = 0.15, tip = 0.35;
        // damage: a band around the crack, fading beyond the tip; opening pushes the halves apart
        const double along = x < tip ? 1.0 : std::exp(-std::pow((x - tip) / 0.03, 2));
        const double d = 0.9 * along * std::exp(-std::pow((y - crack_y) / 0.012, 2));
        const double opening = (y > crack_y ? 1.0 : -1.0) * 0.004 * along;
        g->reference_x.push_back(static_cast<float>(x));
        g->reference_y.push_back(static_cast<float>(y));
        s.px.push_back(static_cast<float>(x));
        s.py.push_back(static_cast<float>(y + opening));
        s.damage.push_back(static_cast<float>(d));
        s.displacement.push_back(static_cast<float>(std::abs(opening) + 0.002 * x));
        s.speed.push_back(static_cast<float>(0.5 * x + 0.2 * y));
        s.strain.push_back(static_cast<float>(0.01 * d));
        g->particle_attached.push_back(i == 0 ? 1 : 0);
      }
    }
    // a small body of 5 x 5 particles whose bonds are drawn
    SceneGeometry::FlexBody chip;
    chip.name = "chip";
    chip.first_particle = nx * ny;
    chip.particle_count = 25;
    chip.grid_spacing = 0.016;
    g->flex_bodies.push_back(chip);
    for (int j = 0; j < 5; ++j) {
      for (int i = 0; i < 5; ++i) {
        const float x = static_cast<float>(0.45 + 0.016 * i), y = static_cast<float>(0.36 + 0.016 * j);
        g->reference_x.push_back(x);
        g->reference_y.push_back(y);
        s.px.push_back(x);
        s.py.push_back(y);
        s.damage.push_back(0.1f * i);
        s.displacement.push_back(0.0f);
        s.speed.push_back(0.1f);
        s.strain.push_back(0.0f);
        g->particle_attached.push_back(0);
      }
    }
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const int k = nx * ny + j * 5 + i;
        if (i + 1 < 5) s.bond_pairs.push_back({k, k + 1});
        if (j + 1 < 5) s.bond_pairs.push_back({k, k + 5});
        if (i + 1 < 5 && j + 1 < 5) s.bond_pairs.push_back({k, k + 6});
      }
  }

  // one marker of every kind, a spring and a probe
  using Kind = Snapshot::Marker::Kind;
  s.markers.push_back({Kind::kRevolute, Vec2(0.75, 0.12), Vec2::Zero()});
  s.markers.push_back({Kind::kDriver, Vec2(0.72, 0.32), Vec2::Zero()});
  s.markers.push_back({Kind::kLink, Vec2(0.81, 0.17), Vec2(0.72, 0.32)});
  s.markers.push_back({Kind::kTranslational, Vec2(-0.3, 0.02), Vec2(-0.05, 0.02)});
  s.markers.push_back({Kind::kRigid, Vec2(-0.2, 0.15), Vec2::Zero()});
  s.markers.push_back({Kind::kAttachment, Vec2(0.01, 0.15), Vec2::Zero()});
  s.springs.push_back({Vec2(-0.25, -0.04), Vec2(-0.2, 0.15)});
  s.probes.push_back({"tip", Vec2(0.35, 0.15)});

  g->bounds_min = Vec2(-0.32, -0.08);
  g->bounds_max = Vec2(0.82, 0.42);
  s.geometry = g;
  s.max_damage = 0.9;
  return s;
}

}  // namespace periflex::testing
