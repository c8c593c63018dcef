// A [[flex_body]]: its shape and grid, notches, the peridynamic material (bond-based or
// state-based, fracture by energy or stretch, softening) and the loads on regions of it.
#include "scene/scene_table_reader.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/file_shape_reader.h"
#include "scene/function_reader.h"
#include "scene/material_law_keys.h"
#include "scene/scene_loader.h"
#include "scene/shape_reader.h"

namespace periflex {

namespace {

using Kind = ShapeDef::Kind;

const std::set<std::string> kLoadKeys = {"name", "type", "region", "fx", "fy"};

}  // namespace

// Young's modulus and density of a material table (the body's or a block's), each in its
// physically meaningful range: beyond them the critical step under- or overflows.
void SceneTableReader::read_modulus_and_density(TableReader& in, double& youngs_modulus, double& density) {
  youngs_modulus = in.required_number("youngs_modulus", Sign::kPositive);
  density = in.required_number("density", Sign::kPositive);
  check_range(in, "youngs_modulus", youngs_modulus, 1e-3, 1e13, "Pa");
  check_range(in, "density", density, 1e-3, 1e6, "kg/m^3");
}

// The fracture criterion of a material table: fracture_energy or critical_stretch (both only where
// the law takes both), one of them while fracture is on, each in its range.
SceneTableReader::FractureKeys SceneTableReader::read_fracture_keys(TableReader& in, bool fracture, bool both_allowed) {
  FractureKeys keys{in.optional_number("fracture_energy", Sign::kPositive),
                    in.optional_number("critical_stretch", Sign::kPositive)};
  if (keys.energy && keys.stretch && !both_allowed)
    in.fail("critical_stretch", "give fracture_energy or critical_stretch, not both");
  if (fracture && !keys.energy && !keys.stretch)
    in.fail_missing("fracture_energy", "or critical_stretch; or set fracture = false in the flexible body");
  if (keys.energy) check_range(in, "fracture_energy", *keys.energy, 1e-12, 1e8, "J/m^2");
  if (keys.stretch) check_range(in, "critical_stretch", *keys.stretch, 1e-12, 10.0, "");
  return keys;
}

FlexBodyDef SceneTableReader::read_flex_body(const toml::table& table, size_t index) {
  FlexBodyDef flex;
  flex.name = element_name(table, "flex_body", index, body_names_);
  TableReader in(context_, table, "flex_body." + flex.name, "[[flex_body]] '" + flex.name + "'");
  in.node("name");
  if (flex.name == "ground") in.fail("name", "'ground' is the name of the implicit ground; choose another");
  flex_names_.insert(flex.name);
  flex.where = in.where();

  // geometry: an area filled with particles, minus holes
  const toml::node* shape = in.node("shape");
  if (shape == nullptr) in.fail_missing("shape");
  // a shape from a file (points, image, dxf) is read once grid_spacing, thickness and holes are known
  const bool from_file = is_file_shape(*shape);
  if (!from_file)
    flex.shape = read_shape(context_, *shape, in.key_path("shape"), {Kind::kBox, Kind::kCircle, Kind::kPolygon, Kind::kBoolean});
  if (const toml::node* holes = in.node("holes")) flex.holes = read_shape_list(context_, *holes, in.key_path("holes"), kRegionShapeKinds);

  // grid and horizon
  flex.grid_spacing = in.required_number("grid_spacing", Sign::kPositive, true);
  flex.thickness = in.number("thickness", flex.thickness, Sign::kPositive, true);
  check_range(in, "thickness", flex.thickness, 1e-9, 1e3, "m");
  if (from_file) read_file_shape(context_, *shape, in.key_path("shape"), scene_.limits, flex);
  flex.horizon_ratio = in.number("horizon_ratio", flex.horizon_ratio, Sign::kPositive);
  // the budget names these where they were set, in the file or by --set
  for (const char* key : {"grid_spacing", "horizon_ratio"}) note_origin(in, key);
  if (flex.horizon_ratio < 1.0)
    in.fail("horizon_ratio", "must be at least 1 (a horizon smaller than the grid spacing has no bonds), found " +
            format_number(flex.horizon_ratio));
  if (flex.horizon_ratio > kMaxHorizonRatio)
    in.fail("horizon_ratio", "must be at most " + format_number(kMaxHorizonRatio) +
                                 " (each particle would have hundreds of thousands of bonds), found " +
                                 format_number(flex.horizon_ratio));
  flex.jitter = in.number("jitter", flex.jitter, Sign::kNonNegative);
  if (!(flex.jitter < 0.5))
    in.fail("jitter", "must be below 0.5 (a particle moved half a spacing could meet its neighbour), found " +
                          format_number(flex.jitter));
  flex.jitter_seed = static_cast<uint64_t>(in.integer("jitter_seed", 1, 0));
  // refuse absurd grids before anything is allocated
  // (a first look from the area; the exact count and the whole scene's budget come after loading)
  const double limit = std::max(kMaxParticlesPerFlexBody, scene_.limits.max_particles);
  const double particles = shape_area(flex.shape) / (flex.grid_spacing * flex.grid_spacing);
  if (!(particles <= limit)) {
    const double smallest = std::sqrt(shape_area(flex.shape) / limit);
    in.fail("grid_spacing", "flexible body '" + flex.name + "' would have about " + format_count(std::round(particles)) +
            " particles (area / grid_spacing^2), more than the limit of " + format_count(limit) +
            " (limits.max_particles); use grid_spacing >= " + format_number(smallest));
  }

  // model options
  const std::string influence = in.choice("influence", {"constant", "conical"}, "constant");
  flex.influence = influence == "conical" ? FlexBodyDef::Influence::kConical : FlexBodyDef::Influence::kConstant;
  flex.partial_volume_correction = in.boolean("partial_volume_correction", flex.partial_volume_correction);
  flex.surface_correction = in.boolean("surface_correction", flex.surface_correction);
  flex.fracture = in.boolean("fracture", flex.fracture);
  flex.bond_damping = in.number("bond_damping", 0.0, Sign::kNonNegative);
  flex.global_damping = in.number("global_damping", 0.0, Sign::kNonNegative);
  flex.velocity = in.vec2("velocity", Vec2::Zero());

  // pre-cracks and unbreakable regions
  if (const toml::array* notches = in.optional_array("notches"))
    for (size_t k = 0; k < notches->size(); ++k) flex.notches.push_back(read_notch(*notches->get(k), in.key_path("notches") + "." + std::to_string(k)));
  const std::string damage = in.choice("damage", {"exclude_notch", "include_notch"}, "exclude_notch");
  flex.damage = damage == "include_notch" ? FlexBodyDef::Damage::kIncludeNotch : FlexBodyDef::Damage::kExcludeNotch;
  if (const toml::node* no_fail = in.node("no_fail"))
    flex.no_fail_regions = read_shape_list(context_, *no_fail, in.key_path("no_fail"), kRegionShapeKinds);

  // material
  const toml::table* material = in.optional_table("material");
  if (material == nullptr) in.fail_missing("material", "a [flex_body.material] table");
  flex.material = read_material(*material, in.key_path("material"), flex.fracture);
  // other materials by block, each block of the point file once
  if (const toml::node* blocks = in.node("block_material")) {
    const auto* array = blocks->as_array();
    if (array == nullptr)
      context_.fail(blocks, in.key_path("block_material"),
                    "expected [[flex_body.block_material]] tables, found " + describe_type(*blocks));
    for (size_t k = 0; k < array->size(); ++k) {
      const toml::node* element = array->get(k);
      const std::string path = in.key_path("block_material") + "." + std::to_string(k);
      if (!element->is_table())
        context_.fail(element, path, "expected [[flex_body.block_material]] tables, found " + describe_type(*element));
      flex.block_materials.push_back(read_block_material(*element->as_table(), path, flex));
    }
  }

  // loads and boundary conditions
  const toml::node* loads = in.node("load");
  if (loads != nullptr) {
    const auto* array = loads->as_array();
    if (array == nullptr)
      context_.fail(loads, in.key_path("load"), "expected [[flex_body.load]] tables, found " + describe_type(*loads));
    std::map<std::string, int> load_names;
    for (size_t k = 0; k < array->size(); ++k) {
      const toml::node* element = array->get(k);
      if (!element->is_table())
        context_.fail(element, in.key_path("load"), "expected [[flex_body.load]] tables, found " + describe_type(*element));
      flex.loads.push_back(read_load(*element->as_table(), k, flex.name, load_names));
    }
  }
  in.finish();
  return flex;
}

NotchDef SceneTableReader::read_notch(const toml::node& node, const std::string& key) {
  const auto* table = node.as_table();
  if (table == nullptr) context_.fail(&node, key, "expected a notch { p1 = [x, y], p2 = [x, y] }, found " + describe_type(node));
  TableReader in(context_, *table, key, "notch '" + key + "'");
  NotchDef notch;
  notch.p1 = in.required_vec2("p1");
  notch.p2 = in.required_vec2("p2");
  if (!((notch.p2 - notch.p1).norm() > 0.0)) in.fail("p2", "a notch needs p1 and p2 to differ");
  in.finish();
  return notch;
}

PdMaterialDef SceneTableReader::read_material(const toml::table& table, const std::string& path, bool fracture) {
  TableReader in(context_, table, path, "[flex_body.material]");
  PdMaterialDef m;
  read_modulus_and_density(in, m.youngs_modulus, m.density);
  // one fracture criterion: energy or stretch (the softening law takes both: its area and its peak)
  m.model = read_material_model(in);
  const bool softening = m.model == PdMaterialDef::Model::kBilinearSoftening;
  const FractureKeys keys = read_fracture_keys(in, fracture, softening);
  const auto& energy = keys.energy;
  const auto& stretch = keys.stretch;
  m.fracture_energy = energy.value_or(0.0);
  m.critical_stretch = stretch.value_or(0.0);
  m.plane_strain = in.choice("plane", {"stress", "strain"}, "stress") == "strain";
  if (softening) read_softening_keys(in, m, energy, stretch);
  // the state-based model takes any admissible Poisson ratio: -1 < nu < 1/2, and in plane
  // stress also nu = 1/2 (an incompressible sheet thins instead; its 2D bulk modulus E/(2(1-nu)) stays finite)
  if (m.model == PdMaterialDef::Model::kStateBased) {
    const auto nu = in.optional_number("poisson_ratio");
    if (!nu) in.fail_missing("poisson_ratio", "model = \"state_based\" needs Poisson's ratio");
    const bool inside = m.plane_strain ? (*nu > -1.0 && *nu < 0.5) : (*nu > -1.0 && *nu <= 0.5);
    if (!inside)
      in.fail("poisson_ratio", "poisson_ratio " + format_number(*nu) + " is outside " +
              (m.plane_strain ? "(-1, 0.5) in plane strain (at 0.5 the 2D bulk modulus is infinite)"
                              : "(-1, 0.5] in plane stress"));
    m.poisson_ratio = *nu;
    in.finish();
    return m;
  }
  // bond-based peridynamics fixes Poisson's ratio: 1/3 in plane stress, 1/4 in plane strain
  if (const auto nu = in.optional_number("poisson_ratio")) {
    const double fixed = m.plane_strain ? 0.25 : 1.0 / 3.0;
    if (std::abs(*nu - fixed) > 0.05)
      in.fail("poisson_ratio", "bond-based peridynamics fixes Poisson's ratio at " + format_number(fixed) + " in plane " +
              (m.plane_strain ? "strain" : "stress") + "; " + format_number(*nu) +
              " cannot be represented (remove poisson_ratio or change plane)");
    m.poisson_ratio = *nu;
  }
  in.finish();
  return m;
}

BlockMaterialDef SceneTableReader::read_block_material(const toml::table& table, const std::string& path,
                                                      const FlexBodyDef& flex) {
  TableReader in(context_, table, path, "[[flex_body.block_material]]");
  BlockMaterialDef m;
  m.where = in.where();
  m.block = in.integer("block", -1, 0);
  if (m.block < 0) in.fail_missing("block", "the block of the point file these constants are for");
  // a block needs a point file whose fourth column names blocks, all of them in this body
  const ParticleCloud* cloud = flex.particles.get();
  if (cloud == nullptr || cloud->block.empty())
    in.fail("block", "materials by block need a shape of type \"points\" whose file has a block column (x, y, volume, block)");
  if (std::find(cloud->block.begin(), cloud->block.end(), m.block) == cloud->block.end())
    in.fail("block", "no point of " + cloud->source + " in this body is in block " + std::to_string(m.block));
  for (const BlockMaterialDef& other : flex.block_materials)
    if (other.block == m.block) in.fail("block", "block " + std::to_string(m.block) + " already has a material");
  // one law for the whole body: only its constants change from block to block
  if (flex.material.model != PdMaterialDef::Model::kBondBased)
    in.fail("block", "materials by block need the body's material.model = \"bond_based\"");
  read_modulus_and_density(in, m.youngs_modulus, m.density);
  const FractureKeys keys = read_fracture_keys(in, flex.fracture, false);
  m.fracture_energy = keys.energy.value_or(0.0);
  m.critical_stretch = keys.stretch.value_or(0.0);
  in.finish();
  return m;
}

RegionLoadDef SceneTableReader::read_load(const toml::table& table, size_t index, const std::string& flex_name,
                        std::map<std::string, int>& names) {
  RegionLoadDef load;
  const std::string kind = "flex_body." + flex_name + ".load";
  load.name = element_name(table, kind, index, names);
  TableReader in(context_, table, kind + "." + load.name, "[[flex_body.load]] '" + load.name + "'");
  in.node("name");
  load.where = in.where();
  const std::string type =
      in.required_choice("type", {"prescribed_velocity", "prescribed_displacement", "traction", "body_force"});
  load.kind = type == "prescribed_velocity"       ? RegionLoadDef::Kind::kPrescribedVelocity
              : type == "prescribed_displacement" ? RegionLoadDef::Kind::kPrescribedDisplacement
              : type == "traction"                ? RegionLoadDef::Kind::kTraction
                                                  : RegionLoadDef::Kind::kBodyForce;
  const toml::node* region = in.node("region");
  if (region == nullptr) in.fail_missing("region");
  load.region = read_shape(context_, *region, in.key_path("region"), kRegionShapeKinds);
  if (const toml::node* fx = in.node("fx")) load.fx = read_time_function(context_, *fx, in.key_path("fx"));
  if (const toml::node* fy = in.node("fy")) load.fy = read_time_function(context_, *fy, in.key_path("fy"));
  // a load with neither component does nothing
  if (!load.fx && !load.fy) in.fail_missing("fx", "or fy; a load needs at least one component");
  in.finish();
  return load;
}

}  // namespace periflex
