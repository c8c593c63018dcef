#include "scene/material_law_keys.h"

namespace periflex {

PdMaterialDef::Model read_material_model(TableReader& in) {
  const std::string model = in.choice("model", {"bond_based", "state_based", "bilinear_softening"}, "bond_based");
  if (model == "state_based") return PdMaterialDef::Model::kStateBased;
  if (model == "bilinear_softening") return PdMaterialDef::Model::kBilinearSoftening;
  return PdMaterialDef::Model::kBondBased;
}

void read_softening_keys(TableReader& in, PdMaterialDef& m, const std::optional<double>& energy,
                         const std::optional<double>& stretch) {
  // the curve's area is G0 whether or not bonds may fail in this run
  if (!energy) in.fail_missing("fracture_energy", "model = \"bilinear_softening\" needs G0, the area under its curve");
  const auto ratio = in.optional_number("softening_ratio", Sign::kPositive);
  if (ratio && stretch)
    in.fail("softening_ratio", "give softening_ratio (s1 / s0) or critical_stretch (s0), not both");
  if (!ratio && !stretch)
    in.fail_missing("softening_ratio", "or critical_stretch: model = \"bilinear_softening\" needs one to place s0");
  // s1 / s0 of 1 is the brittle law; past 1000 the peak force is a thousandth of the brittle one's
  if (ratio && !(*ratio > 1.0 && *ratio <= 1000.0))
    in.fail("softening_ratio", "softening_ratio " + format_number(*ratio) + " is outside (1, 1000]");
  m.softening_ratio = ratio.value_or(0.0);
}

}  // namespace periflex
