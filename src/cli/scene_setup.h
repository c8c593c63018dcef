// Loading a scene for a command: the file, its --set overrides, then the command-line
// options that stand for common overrides (--until, --dt, --integrator).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

// Throws InputError for an unreadable or invalid scene, a bad override or a bad option value.
SceneDef load_scene_with_options(const std::string& path, const std::vector<std::string>& overrides,
                                 std::optional<double> until = {}, std::optional<double> dt = {},
                                 std::optional<std::string> integrator = {});

// The scene run when `periflex` is called without arguments.
std::string default_scene_path();

}  // namespace periflex
