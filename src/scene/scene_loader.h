// Scene files in, SceneDef out: the entry point of the scene layer.
//
//   SceneDef scene = load_scene("scenes/pendulum.toml", {"solver.dt=1e-4", "body.bob.mass=2"});
//
// The file is TOML in the schema of docs/scenes.md. Overrides ("--set key.path=value") are applied
// to the parsed tree before conversion, so they are validated exactly like file values. Every
// problem -- a TOML syntax error, a wrong type, an unknown key, a value out of range, a name that
// refers to nothing -- throws InputError with the file (or "--set"), line, column and dotted key.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/scene_def.h"

namespace periflex {

// A flexible body whose estimated particle count (area / grid_spacing^2) exceeds this is refused
// at once, before its cells are counted (the exact count and the scene's budget follow in
// scene/scene_budget.h).
constexpr double kMaxParticlesPerFlexBody = 2e7;

// Largest scene file read (bytes); PERIFLEX_MAX_SCENE_BYTES raises it. Only regular files are read.
constexpr long kMaxSceneBytes = 16L << 20;

// Longest scene name.
constexpr size_t kMaxSceneNameLength = 100;

// Most projection iterations per step.
constexpr int kMaxProjectionIterations = 1000;

// Reads and validates the scene file at `path`, applying `overrides` ("key.path=value") in order.
// Throws InputError (file unreadable, syntax, schema or validation error).
SceneDef load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// As load_scene, from text already in memory; `display_path` is the file name used in messages,
// in SceneDef::path, and (its stem) as the default scene name.
SceneDef parse_scene(std::string_view toml_text, const std::string& display_path,
                     const std::vector<std::string>& overrides = {});

// The integrator names a scene may ask for (solver.integrator): those of the catalogue
// (scene/integrator_catalogue.h).
const std::vector<std::string>& scene_integrator_names();

}  // namespace periflex
