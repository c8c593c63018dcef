// Reads the keys of a [[contact]] table (docs/scenes.md) once the scene builder has named it
// and resolved its rigid body: the flexible bodies it involves and the contact law.
#pragma once

#include <set>
#include <string>

#include "scene/contact_def.h"
#include "scene/toml_reader.h"

namespace periflex {

// Keys of every contact type, for "does not apply to" messages.
extern const std::set<std::string> kContactKeys;

// The contact type ("rigid_particles" or "particles") of the table, read first so the builder
// knows whether a rigid body is expected.
ContactDef::Kind read_contact_kind(TableReader& in);

// Fills the flexible bodies and the law of `contact` (kind, name and body already set).
// `flex_names` are the declared flexible bodies. Throws InputError at the offending key.
void read_contact_law(TableReader& in, const std::set<std::string>& flex_names, ContactDef& contact);

}  // namespace periflex
