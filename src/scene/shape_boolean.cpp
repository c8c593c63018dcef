#include "scene/shape_boolean.h"

#include <algorithm>

#include "scene/grid_scan.h"
#include "scene/shape_reader.h"
#include "scene/toml_reader.h"

namespace periflex {

bool boolean_contains(const ShapeDef& shape, const Vec2& p) {
  const std::vector<ShapeDef>& o = shape.operands;
  if (o.empty()) return false;
  switch (shape.combine) {
    case ShapeDef::Combine::kUnion:
      return std::any_of(o.begin(), o.end(), [&](const ShapeDef& s) { return s.contains(p); });
    case ShapeDef::Combine::kIntersection:
      return std::all_of(o.begin(), o.end(), [&](const ShapeDef& s) { return s.contains(p); });
    case ShapeDef::Combine::kDifference:
      return o.front().contains(p) && std::none_of(o.begin() + 1, o.end(), [&](const ShapeDef& s) { return s.contains(p); });
  }
  return false;
}

double boolean_area_bound(const ShapeDef& shape) {
  const std::vector<ShapeDef>& o = shape.operands;
  if (o.empty()) return 0.0;
  switch (shape.combine) {
    case ShapeDef::Combine::kUnion: {
      double sum = 0.0;
      for (const ShapeDef& s : o) sum += shape_area(s);
      return sum;
    }
    case ShapeDef::Combine::kIntersection: {
      double smallest = shape_area(o.front());
      for (const ShapeDef& s : o) smallest = std::min(smallest, shape_area(s));
      return smallest;
    }
    case ShapeDef::Combine::kDifference:
      return shape_area(o.front());
  }
  return 0.0;
}

void boolean_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi) {
  const std::vector<ShapeDef>& o = shape.operands;
  lo = hi = Vec2::Zero();
  if (o.empty()) return;
  shape_bounds(o.front(), lo, hi);
  if (shape.combine == ShapeDef::Combine::kDifference) return;
  for (size_t k = 1; k < o.size(); ++k) {
    Vec2 a, b;
    shape_bounds(o[k], a, b);
    if (shape.combine == ShapeDef::Combine::kUnion) {
      lo = lo.cwiseMin(a);
      hi = hi.cwiseMax(b);
    } else {
      lo = lo.cwiseMax(a);
      hi = hi.cwiseMin(b);
    }
  }
}

ShapeDef read_boolean_shape(TableReader& in, const std::string& type, const std::vector<ShapeDef::Kind>& allowed) {
  ShapeDef shape;
  shape.kind = ShapeDef::Kind::kBoolean;
  shape.combine = type == "union"        ? ShapeDef::Combine::kUnion
                  : type == "difference" ? ShapeDef::Combine::kDifference
                                         : ShapeDef::Combine::kIntersection;
  const toml::node* list = in.node("shapes");
  if (list == nullptr) in.fail_missing("shapes", "the shapes to combine");
  shape.operands = read_shape_list(in.context(), *list, in.key_path("shapes"), allowed);
  const size_t needed = shape.combine == ShapeDef::Combine::kUnion ? 1 : 2;
  if (shape.operands.size() < needed)
    in.fail("shapes", "a '" + type + "' needs at least " + std::to_string(needed) + " shapes, found " +
                          std::to_string(shape.operands.size()));
  return shape;
}

}  // namespace periflex
