#include "contact/contact_manifold.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/shape_distance.h"

namespace periflex {

namespace {

// Edge k of a core runs from v[k] to v[k + 1] (wrapping); a two-point core has two edges, the
// segment both ways, with opposite normals.
Vec2 edge_end(const std::vector<Vec2>& v, size_t k) { return v[(k + 1) % v.size()]; }

// Outward unit normal of edge k (counter-clockwise cores); zero for an edge of no length.
Vec2 edge_normal(const std::vector<Vec2>& v, size_t k) {
  const Vec2 e = edge_end(v, k) - v[k];
  const double length = e.norm();
  return length > 0.0 ? Vec2(e.y() / length, -e.x() / length) : Vec2(Vec2::Zero());
}

// How far the core `other` lies outside edge k of `core`: the height of its lowest point above
// the edge's line (negative: below it, a penetration).
double height_above(const std::vector<Vec2>& core, size_t k, const std::vector<Vec2>& other) {
  const Vec2 n = edge_normal(core, k);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec2& w : other) lowest = std::min(lowest, n.dot(w - core[k]));
  return lowest;
}

struct Face {
  double separation = -std::numeric_limits<double>::infinity();
  size_t edge = 0;
};

// The edge of `core` that `other` lies highest above: the axis of least penetration among its
// edge normals.
Face best_face(const std::vector<Vec2>& core, const std::vector<Vec2>& other) {
  Face best;
  for (size_t k = 0; k < core.size(); ++k) {
    if (edge_normal(core, k).isZero()) continue;
    const double h = height_above(core, k, other);
    if (h > best.separation) best = {h, k};
  }
  return best;
}

// A bar's core has no end faces; the gap along its length axis beyond either end (negative:
// overlapping along it) tells two bars in line apart.
double separation_along_length(const std::vector<Vec2>& core, const std::vector<Vec2>& other) {
  if (core.size() != 2 || core[0] == core[1]) return -std::numeric_limits<double>::infinity();
  const Vec2 d = (core[1] - core[0]).normalized();
  double beyond_end = std::numeric_limits<double>::infinity(), before_start = beyond_end;
  for (const Vec2& w : other) {
    beyond_end = std::min(beyond_end, d.dot(w - core[1]));
    before_start = std::min(before_start, -d.dot(w - core[0]));
  }
  return std::max(beyond_end, before_start);
}

// The nearest points of two cores that do not overlap (pa on a, pb on b): the nearest pair over
// every pair of edges, each the nearest of an end point to the other segment.
void nearest_points(const std::vector<Vec2>& a, const std::vector<Vec2>& b, Vec2& pa, Vec2& pb) {
  double best = std::numeric_limits<double>::infinity();
  const size_t edges_a = a.size() == 2 ? 1 : a.size(), edges_b = b.size() == 2 ? 1 : b.size();
  for (size_t i = 0; i < edges_a; ++i) {
    const Vec2 a0 = a[i], a1 = edge_end(a, i);
    for (size_t j = 0; j < edges_b; ++j) {
      const Vec2 b0 = b[j], b1 = edge_end(b, j);
      const auto consider = [&](const Vec2& on_a, const Vec2& on_b) {
        const double d2 = (on_a - on_b).squaredNorm();
        if (d2 < best) {
          best = d2;
          pa = on_a;
          pb = on_b;
        }
      };
      consider(a0, nearest_on_segment(a0, b0, b1));
      consider(a1, nearest_on_segment(a1, b0, b1));
      consider(nearest_on_segment(b0, a0, a1), b0);
      consider(nearest_on_segment(b1, a0, a1), b1);
    }
  }
}

}  // namespace

bool convex_manifold(const std::vector<Vec2>& a, double radius_a, const std::vector<Vec2>& b, double radius_b,
                     ContactManifold& out) {
  out = ContactManifold{};
  if (a.size() < 2 || b.size() < 2) return false;
  const double reach = radius_a + radius_b;
  const Face face_a = best_face(a, b), face_b = best_face(b, a);
  const double face_gap = std::max(face_a.separation, face_b.separation);
  const double gap = std::max({face_gap, separation_along_length(a, b), separation_along_length(b, a)});
  if (gap >= reach) return false;  // an axis on which the rounded shapes' shadows do not meet

  // the reference face: b's, unless a's has clearly less penetration (a tie, as in a symmetric
  // crossing, always picks the same one)
  const double tie = 1e-9 * (std::abs(face_a.separation) + std::abs(face_b.separation) + reach);
  const bool on_a = face_a.separation > face_b.separation + tie;
  const std::vector<Vec2>& reference = on_a ? a : b;
  const std::vector<Vec2>& incident = on_a ? b : a;
  const double incident_radius = on_a ? radius_b : radius_a;
  const size_t face = on_a ? face_a.edge : face_b.edge;
  const Vec2 n = edge_normal(reference, face);
  out.normal = on_a ? Vec2(-n) : n;

  if (gap > 0.0) {
    // cores apart: near a corner (the faces pass below the nearest points) they touch at one point
    Vec2 pa, pb;
    nearest_points(a, b, pa, pb);
    const double distance = (pa - pb).norm();
    if (distance >= reach) return false;
    if (face_gap < distance - 1e-9 * (distance + reach) && distance > 0.0) {
      out.normal = (pa - pb) / distance;
      const double depth = reach - distance;
      out.points[0] = {pa - (radius_a - 0.5 * depth) * out.normal, depth};
      out.count = 1;
      return true;
    }
  }

  // the incident edge: the one whose normal is most opposed to the reference face's
  size_t incident_edge = 0;
  double most_opposed = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < incident.size(); ++k) {
    const Vec2 m = edge_normal(incident, k);
    if (m.isZero()) continue;
    if (n.dot(m) < most_opposed) {
      most_opposed = n.dot(m);
      incident_edge = k;
    }
  }

  // clip it to the reference face's extent along the face
  const Vec2 r1 = reference[face], r2 = edge_end(reference, face);
  const Vec2 along = (r2 - r1).normalized();
  const double lo = along.dot(r1), hi = along.dot(r2);
  const Vec2 p = incident[incident_edge], q = edge_end(incident, incident_edge);
  const double sp = along.dot(p), sq = along.dot(q);
  const bool outside = (sp < lo && sq < lo) || (sp > hi && sq > hi);
  // (an end outside the extent implies sp != sq here: the other end is inside)
  const auto clip = [&](const Vec2& end, double s) {
    if (outside || (s >= lo && s <= hi)) return end;
    const double bound = s < lo ? lo : hi;
    return Vec2(p + (bound - sp) / (sq - sp) * (q - p));
  };
  const Vec2 p_clipped = clip(p, sp), q_clipped = clip(q, sq);

  // each clipped end lower than the two radii above the face touches, at the middle of the
  // overlap along the normal
  const auto add = [&](const Vec2& c) {
    const double depth = reach - n.dot(c - r1);
    if (depth <= 0.0) return;
    out.points[static_cast<size_t>(out.count++)] = {Vec2(c + (0.5 * depth - incident_radius) * n), depth};
  };
  if (!outside) {
    add(p_clipped);
    if ((q_clipped - p_clipped).squaredNorm() > 0.0) add(q_clipped);
  }
  if (out.count == 0) {
    // the deepest corner lies beyond the face's ends: it alone pushes
    const Vec2* deepest = &incident.front();
    for (const Vec2& w : incident)
      if (n.dot(w - r1) < n.dot(*deepest - r1)) deepest = &w;
    add(*deepest);
  }
  return out.count > 0;
}

}  // namespace periflex
