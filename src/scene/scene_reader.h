// Converts a parsed (and overridden) TOML tree into a validated SceneDef: every key is read with
// its type and range checked, unknown keys are refused, and names are resolved (joints, drivers,
// forces, probes and attachments must name declared bodies; names are unique per kind, and
// rigid and flexible bodies share one namespace).
#pragma once

#include <string>

#include <toml++/toml.h>

#include "scene/scene_def.h"
#include "scene/toml_reader.h"

namespace periflex {

// `default_name` is the scene name used when [scene] name is absent (the file stem). The sections'
// readers: scene_reader.cpp, solver_sections.cpp, mechanism_sections.cpp, flex_body_section.cpp,
// coupling_sections.cpp (sharing scene_table_reader.h).
SceneDef read_scene_tables(const toml::table& root, const ReadContext& context, const std::string& default_name);

}  // namespace periflex
