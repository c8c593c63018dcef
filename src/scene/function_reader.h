// Reads a time function from a scene: a plain number (constant) or an inline table
// { type = "constant" | "rate" | "polynomial" | "harmonic" | "table", ... } (docs/scenes.md).
#pragma once

#include <string>

#include <toml++/toml.h>

#include "core/time_function.h"
#include "scene/toml_reader.h"

namespace periflex {

// Converts `node` (found under dotted key `key`) into a TimeFunction; throws InputError on a bad form,
// an unknown type, a missing or unknown key, or a table whose times do not strictly increase.
TimeFunction read_time_function(const ReadContext& context, const toml::node& node, const std::string& key);

}  // namespace periflex
