#include "contact/shape_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace periflex {

namespace {

// Unit vector along d, or `fallback` when d is zero.
Vec2 unit_or(const Vec2& d, const Vec2& fallback) {
  const double length = d.norm();
  return length > 0.0 ? Vec2(d / length) : fallback;
}

ShapeDistance box_distance(const ShapeDef& shape, const Vec2& p) {
  // in the box frame: q = |local| - half extents; outside the corner region the largest q decides
  const Vec2 local = rotation(-shape.angle) * (p - shape.center);
  const Vec2 half(0.5 * shape.width, 0.5 * shape.height);
  const Vec2 q(std::abs(local.x()) - half.x(), std::abs(local.y()) - half.y());
  const Vec2 sign(local.x() < 0.0 ? -1.0 : 1.0, local.y() < 0.0 ? -1.0 : 1.0);
  ShapeDistance out;
  Vec2 normal_local;
  if (q.x() > 0.0 || q.y() > 0.0) {
    const Vec2 outside(std::max(q.x(), 0.0), std::max(q.y(), 0.0));
    out.distance = outside.norm();
    normal_local = Vec2(sign.x() * outside.x(), sign.y() * outside.y()) / out.distance;
  } else if (q.x() > q.y()) {
    out.distance = q.x();
    normal_local = Vec2(sign.x(), 0.0);
  } else {
    out.distance = q.y();
    normal_local = Vec2(0.0, sign.y());
  }
  out.normal = rotation(shape.angle) * normal_local;
  return out;
}

ShapeDistance polygon_distance(const ShapeDef& shape, const Vec2& p) {
  // nearest edge; the sign from the inside test (vertices counter-clockwise)
  const auto& v = shape.vertices;
  const size_t n = v.size();
  double best = std::numeric_limits<double>::infinity();
  Vec2 nearest = v.front(), edge_normal = Vec2::UnitX();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 c = nearest_on_segment(p, v[j], v[i]);
    const double d2 = (p - c).squaredNorm();
    if (d2 < best) {
      best = d2;
      nearest = c;
      const Vec2 edge = v[i] - v[j];
      edge_normal = unit_or(Vec2(edge.y(), -edge.x()), Vec2::UnitX());  // outward for counter-clockwise
    }
  }
  const bool inside = shape.contains(p);
  ShapeDistance out;
  out.distance = (inside ? -1.0 : 1.0) * std::sqrt(best);
  out.normal = (inside ? -1.0 : 1.0) * unit_or(p - nearest, inside ? Vec2(-edge_normal) : edge_normal);
  return out;
}

}  // namespace

ShapeDistance signed_distance(const ShapeDef& shape, const Vec2& p) {
  switch (shape.kind) {
    case ShapeDef::Kind::kBox:
      return box_distance(shape, p);
    case ShapeDef::Kind::kCircle: {
      const Vec2 d = p - shape.center;
      return {d.norm() - shape.radius, unit_or(d, Vec2::UnitX())};
    }
    case ShapeDef::Kind::kBar: {
      const Vec2 d = p - nearest_on_segment(p, shape.p1, shape.p2);
      const Vec2 along = shape.p2 - shape.p1;
      return {d.norm() - shape.radius, unit_or(d, unit_or(Vec2(along.y(), -along.x()), Vec2::UnitY()))};
    }
    case ShapeDef::Kind::kPolygon:
      return polygon_distance(shape, p);
    case ShapeDef::Kind::kNone:
    case ShapeDef::Kind::kBoolean:  // never a contact shape (flexible bodies and regions only)
      break;
  }
  return {std::numeric_limits<double>::infinity(), Vec2::UnitX()};
}

bool is_convex(const std::vector<Vec2>& v) {
  const size_t n = v.size();
  if (n < 3) return false;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 e1 = v[(i + 1) % n] - v[i], e2 = v[(i + 2) % n] - v[(i + 1) % n];
    if (cross(e1, e2) < 0.0) return false;
  }
  return true;
}

void bounding_circle(const ShapeDef& shape, Vec2& centre, double& radius) {
  switch (shape.kind) {
    case ShapeDef::Kind::kBox:
      centre = shape.center;
      radius = 0.5 * std::hypot(shape.width, shape.height);
      return;
    case ShapeDef::Kind::kCircle:
      centre = shape.center;
      radius = shape.radius;
      return;
    case ShapeDef::Kind::kBar:
      centre = 0.5 * (shape.p1 + shape.p2);
      radius = 0.5 * (shape.p2 - shape.p1).norm() + shape.radius;
      return;
    case ShapeDef::Kind::kPolygon: {
      centre = Vec2::Zero();
      for (const Vec2& v : shape.vertices) centre += v;
      centre /= static_cast<double>(std::max<size_t>(1, shape.vertices.size()));
      radius = 0.0;
      for (const Vec2& v : shape.vertices) radius = std::max(radius, (v - centre).norm());
      return;
    }
    case ShapeDef::Kind::kNone:
    case ShapeDef::Kind::kBoolean:
      break;
  }
  centre = Vec2::Zero();
  radius = -std::numeric_limits<double>::infinity();
}

}  // namespace periflex
