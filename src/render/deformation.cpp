#include "render/deformation.h"

#include <algorithm>
#include <cmath>

namespace periflex {

namespace {

// A body's best-fit rigid motion: x ~ c + R(angle) (X - c0), least squares over its particles
// (2D Procrustes: the angle that maximises sum b . R a has tan = sum a x b / sum a . b).
struct RigidFit {
  double c0x = 0, c0y = 0;  // reference centroid
  double cx = 0, cy = 0;    // current centroid
  double cos_a = 1, sin_a = 0;
  // the rigidly moved reference position of a particle
  void place(double X, double Y, double& rx, double& ry) const {
    const double ax = X - c0x, ay = Y - c0y;
    rx = cx + cos_a * ax - sin_a * ay;
    ry = cy + sin_a * ax + cos_a * ay;
  }
};

RigidFit fit_rigid(const Snapshot& s, size_t first, size_t count) {
  const SceneGeometry& g = *s.geometry;
  RigidFit f;
  if (count == 0) return f;
  // centroids, in double: float sums of thousands of particles lose the micrometres that matter
  for (size_t i = first; i < first + count; ++i) {
    f.c0x += g.reference_x[i];
    f.c0y += g.reference_y[i];
    f.cx += s.px[i];
    f.cy += s.py[i];
  }
  const double inv = 1.0 / double(count);
  f.c0x *= inv, f.c0y *= inv, f.cx *= inv, f.cy *= inv;
  double dot = 0.0, cross = 0.0;
  for (size_t i = first; i < first + count; ++i) {
    const double ax = g.reference_x[i] - f.c0x, ay = g.reference_y[i] - f.c0y;
    const double bx = s.px[i] - f.cx, by = s.py[i] - f.cy;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
  }
  const double angle = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
  f.cos_a = std::cos(angle);
  f.sin_a = std::sin(angle);
  return f;
}

// the particle range [first, first + count) of each flexible body, clipped to what the snapshot holds
template <class Visit>
void for_each_body(const Snapshot& s, Visit visit) {
  if (!s.geometry) return;
  const size_t n = std::min({s.px.size(), s.py.size(), s.geometry->reference_x.size(),
                             s.geometry->reference_y.size()});
  for (const auto& fb : s.geometry->flex_bodies) {
    const size_t first = std::min<size_t>(std::max(fb.first_particle, 0), n);
    const size_t count = std::min<size_t>(std::max(fb.particle_count, 0), n - first);
    if (count > 0) visit(first, count);
  }
}

}  // namespace

void magnify_deformation(const Snapshot& s, double factor, std::vector<float>& x, std::vector<float>& y) {
  x = s.px;
  y = s.py;
  // magnified = rigid + K (current - rigid)
  for_each_body(s, [&](size_t first, size_t count) {
    const RigidFit f = fit_rigid(s, first, count);
    const SceneGeometry& g = *s.geometry;
    for (size_t i = first; i < first + count; ++i) {
      double rx = 0, ry = 0;
      f.place(g.reference_x[i], g.reference_y[i], rx, ry);
      x[i] = static_cast<float>(rx + factor * (s.px[i] - rx));
      y[i] = static_cast<float>(ry + factor * (s.py[i] - ry));
    }
  });
}

Vec2 RigidShift::apply(const Vec2& p) const {
  const double c = std::cos(angle), s = std::sin(angle);
  const Vec2 a = p - from;
  return to + Vec2(c * a.x() - s * a.y(), s * a.x() + c * a.y());
}

Vec2 magnified_probe(const Snapshot::Probe& probe, const std::vector<float>& x, const std::vector<float>& y,
                     const std::vector<RigidShift>& shifts) {
  const size_t particle = static_cast<size_t>(probe.particle);
  if (probe.particle >= 0 && particle < x.size() && particle < y.size()) return Vec2(x[particle], y[particle]);
  const size_t body = static_cast<size_t>(probe.body);
  if (probe.body > 0 && body < shifts.size()) return shifts[body].apply(probe.position);
  return probe.position;
}

std::vector<RigidShift> magnified_body_shifts(const Snapshot& s, const std::vector<float>& x,
                                              const std::vector<float>& y) {
  if (!s.geometry) return {};
  const SceneGeometry& g = *s.geometry;
  std::vector<RigidShift> shifts(g.bodies.size());
  const size_t n = std::min({s.px.size(), s.py.size(), x.size(), y.size(), g.particle_body.size()});
  for (size_t b = 1; b < g.bodies.size(); ++b) {
    if (!g.bodies[b].is_virtual) continue;
    // the centroids of its particles, true and magnified (double sums, as in fit_rigid)
    double cx = 0, cy = 0, mx = 0, my = 0;
    long count = 0;
    for (size_t i = 0; i < n; ++i) {
      if (g.particle_body[i] != static_cast<int>(b)) continue;
      cx += s.px[i], cy += s.py[i], mx += x[i], my += y[i];
      ++count;
    }
    if (count == 0) continue;
    cx /= count, cy /= count, mx /= count, my /= count;
    // the turn between them (2D Procrustes)
    double dot = 0.0, cross = 0.0;
    for (size_t i = 0; i < n; ++i) {
      if (g.particle_body[i] != static_cast<int>(b)) continue;
      const double ax = s.px[i] - cx, ay = s.py[i] - cy, bx = x[i] - mx, by = y[i] - my;
      dot += ax * bx + ay * by;
      cross += ax * by - ay * bx;
    }
    shifts[b].from = Vec2(cx, cy);
    shifts[b].to = Vec2(mx, my);
    shifts[b].angle = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
    shifts[b].moves = true;
  }
  return shifts;
}

double largest_relative_deformation(const Snapshot& s) {
  double largest = 0.0;
  for_each_body(s, [&](size_t first, size_t count) {
    const RigidFit f = fit_rigid(s, first, count);
    const SceneGeometry& g = *s.geometry;
    // the body's size: the diagonal of its reference bounds
    const auto [xlo, xhi] = std::minmax_element(g.reference_x.begin() + first, g.reference_x.begin() + first + count);
    const auto [ylo, yhi] = std::minmax_element(g.reference_y.begin() + first, g.reference_y.begin() + first + count);
    const double size = std::hypot(double(*xhi) - *xlo, double(*yhi) - *ylo);
    if (!(size > 0.0)) return;
    double d2 = 0.0;
    for (size_t i = first; i < first + count; ++i) {
      double rx = 0, ry = 0;
      f.place(g.reference_x[i], g.reference_y[i], rx, ry);
      d2 = std::max(d2, (s.px[i] - rx) * (s.px[i] - rx) + (s.py[i] - ry) * (s.py[i] - ry));
    }
    largest = std::max(largest, std::sqrt(d2) / size);
  });
  return largest;
}

double auto_deform_factor(const Snapshot& s) {
  if (!s.geometry || !s.geometry->has_particles()) return 1.0;
  const double relative = largest_relative_deformation(s);
  // nothing deformed yet (or a non-finite position): the largest factor
  if (!(relative > 0.0) || !std::isfinite(relative)) return relative == 0.0 ? kMaxAutoDeform : 1.0;
  return std::clamp(round_down_125(kAutoDeformShare / relative), 1.0, kMaxAutoDeform);
}

double round_down_125(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  // a little slack so that 100 is not rounded to 50 by the logarithm's last bit
  const double m = value / decade * (1.0 + 1e-12);
  return (m >= 5.0 ? 5.0 : m >= 2.0 ? 2.0 : 1.0) * decade;
}

}  // namespace periflex
