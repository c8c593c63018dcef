// Trails of rigid body centres and probes (trails.h).
#include "render/trails.h"

#include <algorithm>

namespace periflex {

void Trails::record(const Snapshot& s, int max_points) {
  // start over when the scene changes or time runs backwards (reset, reload)
  if (s.geometry.get() != geometry_ || s.time < time_) {
    lines_.clear();
    geometry_ = s.geometry.get();
  }
  time_ = s.time;
  std::vector<Vec2> points;
  if (s.geometry) {
    const size_t nb = std::min(s.geometry->bodies.size(), s.bodies.size());
    for (size_t k = 0; k < nb; ++k)
      if (!s.geometry->bodies[k].ground) points.emplace_back(s.bodies[k].x, s.bodies[k].y);
  }
  for (const auto& p : s.probes) points.push_back(p.position);
  if (lines_.size() != points.size()) lines_.assign(points.size(), {});
  for (size_t i = 0; i < points.size(); ++i) {
    auto& t = lines_[i];
    if (!t.empty() && (t.back() - points[i]).squaredNorm() == 0.0) continue;
    t.push_back(points[i]);
    while (static_cast<int>(t.size()) > std::max(2, max_points)) t.pop_front();
  }
}

void Trails::clear() {
  lines_.clear();
  time_ = -1e300;
}

}  // namespace periflex
