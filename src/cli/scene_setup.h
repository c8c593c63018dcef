// Loading a scene for a command: the file, its --set overrides, then the command-line
// options that stand for common overrides (--until, --dt, --integrator); then the checks that
// relate values to each other and the scene's budget (scene/scene_budget.h), and the warnings
// about geometry that does nothing, printed to stderr.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene_budget.h"
#include "scene/scene_def.h"

namespace periflex {

// Where a command-line value is reported: "command line: key '--dt'".
SourceLocation flag_location(const std::string& flag);

// Throws InputError for an unreadable or invalid scene, a bad override or a bad option value,
// or a scene over its budget.
SceneDef load_scene_with_options(const std::string& path, const std::vector<std::string>& overrides,
                                 std::optional<double> until = {}, std::optional<double> dt = {},
                                 std::optional<std::string> integrator = {}, const RunPlan& plan = {});

// The scene run when `periflex` is called without arguments.
std::string default_scene_path();

}  // namespace periflex
