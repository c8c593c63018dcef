// A flexible body's geometry from a file: `shape = { type = "points" | "image" | "dxf", file = ... }`
// (docs/scenes.md, "Shapes from files"). The file's path is relative to the scene file.
//
//   points  the particles themselves (scene/point_file_reader.h), on the body's grid or off it
//   image   pixels darker than a threshold are material, sampled at the grid spacing
//           (scene/image_shape.h)
//   dxf     closed outlines: the outer loop material, the inner loops holes (scene/dxf_shape.h)
#pragma once

#include <string>

#include <toml++/toml.h>

#include "scene/scene_def.h"
#include "scene/toml_reader.h"

namespace periflex {

// The shape types read from a file.
bool is_file_shape(const toml::node& node);

// Reads the shape at `node` (dotted key `key`) into `flex`, whose grid_spacing, thickness and
// holes are already read: a cloud of particles (points, image; the holes leave theirs out) or a
// polygon with holes (dxf). A file over limits.max_particles is refused before its points are
// stored. Throws InputError naming the scene key, or the file and its line.
void read_file_shape(const ReadContext& context, const toml::node& node, const std::string& key,
                     const LimitsDef& limits, FlexBodyDef& flex);

// The file a flexible body's shape was read from (its path as opened), or "" for a shape typed in
// the scene: what the window watches for its hot reload.
std::string geometry_file(const FlexBodyDef& flex);

// The path of `file` as written in a scene read from `scene_file`: relative to its folder.
std::string scene_relative_path(const std::string& scene_file, const std::string& file);

}  // namespace periflex
