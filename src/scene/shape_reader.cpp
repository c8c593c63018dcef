#include "scene/shape_reader.h"

#include <algorithm>
#include <cmath>

#include "scene/shape_boolean.h"

namespace periflex {

const char* shape_kind_name(ShapeDef::Kind kind) {
  switch (kind) {
    case ShapeDef::Kind::kNone: return "none";
    case ShapeDef::Kind::kBox: return "box";
    case ShapeDef::Kind::kCircle: return "circle";
    case ShapeDef::Kind::kPolygon: return "polygon";
    case ShapeDef::Kind::kBar: return "bar";
    case ShapeDef::Kind::kBoolean: return "union";
  }
  return "none";
}

double polygon_signed_area(const std::vector<Vec2>& vertices) {
  // shoelace formula
  double twice = 0.0;
  for (size_t i = 0, n = vertices.size(); i < n; ++i) twice += cross(vertices[i], vertices[(i + 1) % n]);
  return 0.5 * twice;
}

double shape_area(const ShapeDef& shape) {
  switch (shape.kind) {
    case ShapeDef::Kind::kNone: return 0.0;
    case ShapeDef::Kind::kBox: return shape.width * shape.height;
    case ShapeDef::Kind::kCircle: return kPi * shape.radius * shape.radius;
    case ShapeDef::Kind::kPolygon: return std::abs(polygon_signed_area(shape.vertices));
    // a stadium: the swept rectangle plus the two half discs at the ends
    case ShapeDef::Kind::kBar: return (shape.p2 - shape.p1).norm() * 2.0 * shape.radius + kPi * shape.radius * shape.radius;
    case ShapeDef::Kind::kBoolean: return boolean_area_bound(shape);
  }
  return 0.0;
}

ShapeDef read_shape(const ReadContext& context, const toml::node& node, const std::string& key,
                    const std::vector<ShapeDef::Kind> allowed) {
  const auto* table = node.as_table();
  if (table == nullptr)
    context.fail(&node, key, "expected a shape (an inline table with a type), found " + describe_type(node));

  // the type names the allowed kinds only
  std::vector<std::string> names;
  for (ShapeDef::Kind kind : allowed) {
    if (kind != ShapeDef::Kind::kBoolean) names.emplace_back(shape_kind_name(kind));
    else names.insert(names.end(), {"union", "difference", "intersection"});
  }
  TableReader in(context, *table, key, "shape '" + key + "'");
  const std::string type = in.required_choice("type", names);

  ShapeDef shape;
  if (type == "union" || type == "difference" || type == "intersection") {
    // other shapes combined, each of them any shape allowed here
    shape = read_boolean_shape(in, type, allowed);
    in.finish({}, "a '" + type + "' shape");
    return shape;
  }
  if (type == "box") {
    shape.kind = ShapeDef::Kind::kBox;
    shape.center = in.vec2("center", Vec2::Zero());
    shape.width = in.required_number("width", Sign::kPositive, true);
    shape.height = in.required_number("height", Sign::kPositive, true);
    shape.angle = in.number("angle", 0.0);
  } else if (type == "circle") {
    shape.kind = ShapeDef::Kind::kCircle;
    shape.center = in.vec2("center", Vec2::Zero());
    shape.radius = in.required_number("radius", Sign::kPositive, true);
  } else if (type == "polygon") {
    shape.kind = ShapeDef::Kind::kPolygon;
    const toml::node* list = in.node("vertices");
    if (list == nullptr) in.fail_missing("vertices");
    const auto* array = list->as_array();
    if (array == nullptr) in.fail("vertices", "expected an array of [x, y] vertices, found " + describe_type(*list));
    for (const toml::node& vertex : *array) shape.vertices.push_back(read_vec2(context, vertex, in.key_path("vertices")));
    // a polygon needs an inside
    if (shape.vertices.size() < 3)
      in.fail("vertices", "a polygon needs at least 3 vertices, found " + std::to_string(shape.vertices.size()));
    const double area = polygon_signed_area(shape.vertices);
    double extent = 0.0;
    for (const Vec2& v : shape.vertices) extent = std::max(extent, (v - shape.vertices.front()).norm());
    if (!(std::abs(area) > 1e-14 * extent * extent))
      in.fail("vertices", "the polygon encloses no area (are its vertices collinear or repeated?)");
    // the schema asks for counter-clockwise; accept clockwise by reversing it
    if (area < 0.0) std::reverse(shape.vertices.begin(), shape.vertices.end());
  } else {
    shape.kind = ShapeDef::Kind::kBar;
    shape.p1 = in.required_vec2("p1");
    shape.p2 = in.required_vec2("p2");
    shape.radius = 0.5 * in.required_number("width", Sign::kPositive, true);
    if (!((shape.p2 - shape.p1).norm() > 0.0)) in.fail("p2", "a bar needs p1 and p2 to differ");
  }
  in.finish({"center", "width", "height", "angle", "radius", "vertices", "p1", "p2", "shapes"}, "a '" + type + "' shape");
  return shape;
}

std::vector<ShapeDef> read_shape_list(const ReadContext& context, const toml::node& node, const std::string& key,
                                      const std::vector<ShapeDef::Kind> allowed) {
  const auto* array = node.as_array();
  if (array == nullptr) context.fail(&node, key, "expected an array of shapes, found " + describe_type(node));
  std::vector<ShapeDef> shapes;
  for (size_t k = 0; k < array->size(); ++k)
    shapes.push_back(read_shape(context, *array->get(k), key + "." + std::to_string(k), allowed));
  return shapes;
}

}  // namespace periflex
