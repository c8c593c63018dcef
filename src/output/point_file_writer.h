// A run's flexible bodies as a point file (the format scene/point_file_reader.h reads): every
// particle's reference position [m], volume [m^3] and no-fail flag, the block being the body's
// number (1 for the scene's first flexible body). Numbers are written in the shortest form that
// reads back as the same double, so a body written out and read back is the same body.
#pragma once

#include <string>

#include "scene/scene_def.h"

namespace periflex {

// The file's text for every flexible body of `scene`.
std::string point_file_text(const SceneDef& scene);

// Writes it to `path` atomically. Throws std::runtime_error naming the path on failure.
void write_point_file(const std::string& path, const SceneDef& scene);

}  // namespace periflex
