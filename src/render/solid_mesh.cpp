#include "render/solid_mesh.h"

#include <algorithm>
#include <cmath>

namespace periflex {

namespace {

double signed_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += cross(p[j], p[i]);
  return 0.5 * a;
}

// true when q is inside or on the counter-clockwise triangle abc
bool in_triangle(const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross(b - a, q - a) >= 0.0 && cross(c - b, q - b) >= 0.0 && cross(a - c, q - c) >= 0.0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& points) {
  std::vector<std::array<int, 3>> out;
  const int n = static_cast<int>(points.size());
  if (n < 3) return out;
  // work on a counter-clockwise list of indices
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  if (signed_area(points) < 0.0) std::reverse(idx.begin(), idx.end());

  // ear clipping: cut a convex corner whose triangle holds no other vertex, repeat
  int guard = 0;
  while (idx.size() > 3 && guard < 4 * n * n) {
    bool cut = false;
    const int m = static_cast<int>(idx.size());
    for (int k = 0; k < m; ++k) {
      const int ia = idx[(k + m - 1) % m], ib = idx[k], ic = idx[(k + 1) % m];
      const Vec2 &a = points[ia], &b = points[ib], &c = points[ic];
      ++guard;
      if (cross(b - a, c - b) <= 0.0) continue;  // reflex or flat corner
      bool empty = true;
      for (int j : idx) {
        if (j == ia || j == ib || j == ic) continue;
        if (in_triangle(points[j], a, b, c)) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({ia, ib, ic});
      idx.erase(idx.begin() + k);
      cut = true;
      break;
    }
    if (!cut) break;  // degenerate: finish with a fan below
  }
  for (size_t k = 1; k + 1 < idx.size(); ++k) out.push_back({idx[0], idx[k], idx[k + 1]});
  return out;
}

void SolidMesh::triangle(const Vec2& a, const Vec2& b, const Vec2& c, Rgba8 color) {
  push(a, color);
  push(b, color);
  push(c, color);
}

void SolidMesh::fill_polygon(const std::vector<Vec2>& points, Rgba8 color) {
  for (const auto& t : triangulate_polygon(points)) triangle(points[t[0]], points[t[1]], points[t[2]], color);
}

void SolidMesh::line(const Vec2& a, const Vec2& b, double width_px, Rgba8 color) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len <= 0.0) return;
  const Vec2 n = perp(d / len) * (0.5 * width_px * px_);
  triangle(a - n, b - n, b + n, color);
  triangle(a - n, b + n, a + n, color);
}

void SolidMesh::polyline(const std::vector<Vec2>& points, bool closed, double width_px, Rgba8 color) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return;
  const double half = 0.5 * width_px * px_;
  // offset of each vertex: the mitre of the two neighbouring segment normals
  auto normal = [&](int i, int j) {
    const Vec2 d = points[j] - points[i];
    const double len = d.norm();
    return len > 0.0 ? Vec2(perp(d / len)) : Vec2(0.0, 0.0);
  };
  std::vector<Vec2> offset(n);
  for (int i = 0; i < n; ++i) {
    const bool has_prev = closed || i > 0, has_next = closed || i + 1 < n;
    const Vec2 n_prev = has_prev ? normal((i + n - 1) % n, i) : Vec2(0, 0);
    const Vec2 n_next = has_next ? normal(i, (i + 1) % n) : Vec2(0, 0);
    Vec2 m = n_prev + n_next;
    const double ml = m.norm();
    if (ml < 1e-12) {
      offset[i] = (has_next ? n_next : n_prev) * half;
      continue;
    }
    m /= ml;
    const Vec2 ref = has_next ? n_next : n_prev;
    const double cos_half = std::max(m.dot(ref), 0.34);  // mitre limit about 3 widths
    offset[i] = m * (half / cos_half);
  }
  const int segments = closed ? n : n - 1;
  for (int s = 0; s < segments; ++s) {
    const int i = s, j = (s + 1) % n;
    triangle(points[i] - offset[i], points[j] - offset[j], points[j] + offset[j], color);
    triangle(points[i] - offset[i], points[j] + offset[j], points[i] + offset[i], color);
  }
}

void SolidMesh::dashed_polyline(const std::vector<Vec2>& points, bool closed, double width_px, double dash_px,
                                double gap_px, Rgba8 color) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return;
  const double dash = dash_px * px_, gap = gap_px * px_;
  if (dash <= 0.0) return;
  // walk the path with the state (drawing or skipping) and what is left of it carried across
  // segments, so dashes flow around corners
  bool drawing = true;
  double left = dash;
  const int segments = closed ? n : n - 1;
  for (int s = 0; s < segments; ++s) {
    const Vec2 a = points[s], b = points[(s + 1) % n];
    const double len = (b - a).norm();
    if (len <= 0.0) continue;
    const Vec2 u = (b - a) / len;
    double t = 0.0;
    while (len - t > 0.0) {
      const double step = std::min(left, len - t);
      if (drawing) line(a + t * u, a + (t + step) * u, width_px, color);
      t += step;
      left -= step;
      if (left <= 0.0) {
        drawing = !drawing;
        left = drawing ? dash : std::max(gap, 1e-9 * dash);
      }
    }
  }
}

void SolidMesh::disc(const Vec2& center, double radius, Rgba8 color, int segments) {
  Vec2 prev = center + Vec2(radius, 0.0);
  for (int i = 1; i <= segments; ++i) {
    const double t = 2.0 * kPi * i / segments;
    const Vec2 p = center + radius * Vec2(std::cos(t), std::sin(t));
    triangle(center, prev, p, color);
    prev = p;
  }
}

void SolidMesh::ring_px(const Vec2& center, double radius_px, double width_px, Rgba8 color) {
  std::vector<Vec2> pts;
  for (int i = 0; i < 20; ++i) {
    const double t = 2.0 * kPi * i / 20;
    pts.push_back(center + radius_px * px_ * Vec2(std::cos(t), std::sin(t)));
  }
  polyline(pts, true, width_px, color);
}

void SolidMesh::square_px(const Vec2& center, double half_px, Rgba8 color, bool diamond) {
  const double h = half_px * px_;
  if (diamond) {
    triangle(center + Vec2(h, 0), center + Vec2(0, h), center + Vec2(-h, 0), color);
    triangle(center + Vec2(h, 0), center + Vec2(-h, 0), center + Vec2(0, -h), color);
  } else {
    triangle(center + Vec2(-h, -h), center + Vec2(h, -h), center + Vec2(h, h), color);
    triangle(center + Vec2(-h, -h), center + Vec2(h, h), center + Vec2(-h, h), color);
  }
}

void SolidMesh::cross_px(const Vec2& center, double half_px, double width_px, Rgba8 color) {
  const double h = half_px * px_;
  line(center + Vec2(-h, -h), center + Vec2(h, h), width_px, color);
  line(center + Vec2(-h, h), center + Vec2(h, -h), width_px, color);
}

void SolidMesh::zigzag(const Vec2& a, const Vec2& b, int zigs, double amplitude, double width_px, Rgba8 color) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len <= 0.0) return;
  const Vec2 u = d / len, n = perp(u);
  // straight leads of 15% at each end, teeth alternating either side in between
  std::vector<Vec2> pts{a, a + 0.15 * len * u};
  const double body = 0.7 * len;
  for (int k = 0; k < zigs; ++k) {
    const double s = 0.15 * len + body * (k + 0.5) / zigs;
    pts.push_back(a + s * u + ((k % 2) ? -amplitude : amplitude) * n);
  }
  pts.push_back(a + 0.85 * len * u);
  pts.push_back(b);
  polyline(pts, false, width_px, color);
}

}  // namespace periflex
