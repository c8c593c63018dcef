// "--set key.path=value" overrides, applied to the parsed TOML tree before conversion so that
// overridden values are validated exactly like values from the file.
//
//   solver.dt=1e-4                       a key of a table
//   scene.gravity=[0,-1.62]              any TOML value: numbers, booleans, strings, arrays, inline tables
//   body.crank.mass=2                    [[body]] elements are addressed by name ...
//   flex_body.0.grid_spacing=5e-4        ... or by 0-based index
//   driver.crank_speed.function.rate=10  keys inside inline tables
//   solver.integrator=rk4                a bare word is taken as a string
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

#include "scene/toml_reader.h"

namespace periflex {

// Keys whose values are arrays of tables addressed by element name in override paths.
bool is_array_of_tables_key(std::string_view key);

// Applies each override in order to `root`. Nodes it inserts are recorded in
// context.override_origin so later errors point at the override. Throws InputError located at
// "--set" for a malformed override, an unknown element name or index, or a path through a value.
void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, ReadContext& context);

}  // namespace periflex
