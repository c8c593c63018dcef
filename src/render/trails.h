// Trails: one polyline per rigid body centre and per probe, the last points each has passed
// through, kept between frames and started over when the scene changes or time runs backwards.
// No GL: the marker pass draws them (marker_pass.cpp).
#pragma once

#include <deque>
#include <vector>

#include "core/vec2.h"
#include "solve/snapshot.h"

namespace periflex {

class Trails {
 public:
  // Adds the snapshot's body centres (ground left out) and probes, each to its own trail of at
  // most max(2, max_points) points; a point where the trail already ends is not repeated.
  void record(const Snapshot& s, int max_points);
  // Forgets every trail (the next snapshot starts them afresh).
  void clear();
  // Oldest point first; bodies in snapshot order, then probes.
  const std::vector<std::deque<Vec2>>& lines() const { return lines_; }

 private:
  const SceneGeometry* geometry_ = nullptr;
  double time_ = -1e300;
  std::vector<std::deque<Vec2>> lines_;
};

}  // namespace periflex
