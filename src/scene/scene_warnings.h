// Geometry that is valid but does nothing: a notch no bond crosses, a probe far from every
// particle, two attachments holding the same particles, a load or attachment region with no
// particle in it. `check` prints these, and `run` before it starts. Each warning is located
// like an error ("file:line:column: key 'flex_body.plate.notches.0': ...").
#pragma once

#include <string>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

// The warnings of a scene that has passed check_scene_budget (the scans here stay within it).
std::vector<std::string> scene_warnings(const SceneDef& scene);

}  // namespace periflex
