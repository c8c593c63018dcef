// Reads a shape from a scene: an inline table { type = "box" | "circle" | "polygon" | "bar", ... }
// (docs/scenes.md), and estimates shape areas for the particle-count guard.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

#include "scene/scene_def.h"
#include "scene/toml_reader.h"

namespace periflex {

// Converts `node` (under dotted key `key`) into a ShapeDef whose kind is one of `allowed`.
// Polygons given clockwise are reversed to counter-clockwise; degenerate shapes are refused.
ShapeDef read_shape(const ReadContext& context, const toml::node& node, const std::string& key,
                    const std::vector<ShapeDef::Kind> allowed = {ShapeDef::Kind::kBox, ShapeDef::Kind::kCircle,
                                                                 ShapeDef::Kind::kPolygon, ShapeDef::Kind::kBar});

// Reads an array of shapes (holes, no-fail regions, several drawing shapes).
std::vector<ShapeDef> read_shape_list(const ReadContext& context, const toml::node& node, const std::string& key,
                                      const std::vector<ShapeDef::Kind> allowed = {
                                          ShapeDef::Kind::kBox, ShapeDef::Kind::kCircle, ShapeDef::Kind::kPolygon,
                                          ShapeDef::Kind::kBar});

// Every kind a flexible body's shape, holes, no-fail zones and regions may have: the rigid
// body's kinds and unions, differences and intersections of them.
const std::vector<ShapeDef::Kind> kRegionShapeKinds = {ShapeDef::Kind::kBox, ShapeDef::Kind::kCircle,
                                                       ShapeDef::Kind::kPolygon, ShapeDef::Kind::kBar,
                                                       ShapeDef::Kind::kBoolean};

// Area enclosed by the shape (0 for kNone; for a boolean shape a bound from above).
double shape_area(const ShapeDef& shape);

// Signed area of a polygon: positive when counter-clockwise.
double polygon_signed_area(const std::vector<Vec2>& vertices);

// Schema name of a shape kind ("box", ...).
const char* shape_kind_name(ShapeDef::Kind kind);

}  // namespace periflex
