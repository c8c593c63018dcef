// The keys of [flex_body.material] that choose and shape its peridynamic law: `model` and the
// keys only one law takes (docs/scenes.md, [flex_body.material]).
#pragma once

#include <optional>

#include "scene/scene_def.h"
#include "scene/toml_reader.h"

namespace periflex {

// `model`: "bond_based" (default), "state_based" or "bilinear_softening".
PdMaterialDef::Model read_material_model(TableReader& in);

// model = "bilinear_softening": fracture_energy (G0, the area under the curve) and one of
// softening_ratio (s1 / s0, above 1) or critical_stretch (s0) into m; energy and stretch are the
// values the material's reader found.
void read_softening_keys(TableReader& in, PdMaterialDef& m, const std::optional<double>& energy,
                         const std::optional<double>& stretch);

}  // namespace periflex
