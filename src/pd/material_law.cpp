#include "pd/material_law.h"

#include "core/error.h"
#include "pd/bilinear_softening_law.h"
#include "pd/bond_based_law.h"
#include "pd/state_based_law.h"

namespace periflex {

long MaterialLaw::add_forces_breaking(const BondStore&, BondState&, const LawEvaluation&, const uint8_t*,
                                      std::vector<uint8_t>&, double, double&) {
  return 0;
}

void require_material(const FlexBodyDef& def, bool ok, const std::string& key, const std::string& message) {
  if (ok) return;
  SourceLocation where = def.where;
  const std::string path = "material." + key;
  where.key = where.key.empty() ? path : where.key + "." + path;
  throw InputError(where, "flex body '" + def.name + "': " + message);
}

void warn_unbreakable(std::vector<std::string>& warnings) {
  warnings.emplace_back(
      "fracture is on but neither fracture_energy nor critical_stretch is given; bonds will not break");
}

std::unique_ptr<MaterialLaw> make_material_law(const FlexBodyDef& def, double horizon, double volume,
                                               std::vector<std::string>& warnings) {
  switch (def.material.model) {
    case PdMaterialDef::Model::kStateBased:
      return std::make_unique<StateBasedLaw>(def, horizon, volume, warnings);
    case PdMaterialDef::Model::kBilinearSoftening:
      return std::make_unique<BilinearSofteningLaw>(def, horizon, warnings);
    case PdMaterialDef::Model::kBondBased:
      break;
  }
  return std::make_unique<BondBasedLaw>(def, horizon, warnings);
}

}  // namespace periflex
