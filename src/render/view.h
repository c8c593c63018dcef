// What part of the world a picture should show: bounds of a snapshot and the default camera.
// Shared by the GUI (fit on load, "fit" button) and the recorder (fit, then grow when particles fly
// out).
#pragma once

#include "render/camera.h"
#include "solve/snapshot.h"

namespace periflex {

// Axis-aligned box; empty when lo > hi.
struct Bounds {
  Vec2 lo = Vec2(1.0, 1.0), hi = Vec2(-1.0, -1.0);
  bool empty() const { return lo.x() > hi.x() || lo.y() > hi.y(); }
  void add(const Vec2& p);
  void add(const Bounds& b);
  // true when other lies inside this box
  bool contains(const Bounds& other) const;
};

// Current particle positions only.
Bounds particle_bounds(const Snapshot& snapshot);
// Everything drawn in the snapshot now: particles, body shapes at their poses, markers, springs,
// probes.
Bounds snapshot_bounds(const Snapshot& snapshot);
// The scene's initial bounds (SceneGeometry::bounds_min/max) when set, else snapshot_bounds.
Bounds scene_bounds(const Snapshot& snapshot);
// Multisamples a picture of `particles` particles gets unless the user chooses: 4 for smooth
// edges, but off from kLargeSceneParticles on, where the software renderer (Mesa llvmpipe) pays
// more for the samples than for the particles.
constexpr long kLargeSceneParticles = 100000;
inline int default_samples(long particles) { return particles < kLargeSceneParticles ? 4 : 1; }

// A camera showing scene_bounds with a margin, for a viewport of width x height pixels.
Camera fit_camera(const Snapshot& snapshot, int width, int height, double margin = 0.08);
// Widens the camera (never narrows it) to everything drawn in the snapshot when some of it is
// outside the view of a width x height picture: how a recording's view follows a scene.
void widen_to_show(Camera& camera, const Snapshot& snapshot, int width, int height);

}  // namespace periflex
