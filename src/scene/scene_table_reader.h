// The reader of a scene's TOML tables: turns the tree into a SceneDef one section at a time,
// keeping the names declared so far so that references resolve as they are read. Not a public
// header (scene_reader.h is): only the files that read the sections include it.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "scene/scene_def.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace scene_tables {

// "a, b, c"
inline std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k) out += (k ? ", " : "") + words[k];
  return out;
}

}  // namespace scene_tables

// Turns a TOML tree into a SceneDef, one section at a time.
class SceneTableReader {
 public:
  SceneTableReader(const ReadContext& context, const toml::table& root)
      : context_(context), top_(context, root, "", "the scene file") {}

  SceneDef read(const std::string& default_name);

 private:
  // ---------------------------------------------------------------------------
  // Element lists, names and references (scene_reader.cpp)

  // The tables of the array of tables `key` (e.g. every [[body]]), with their indices.
  std::vector<std::pair<const toml::table*, size_t>> elements(const std::string& key);

  // The required, well-formed, per-kind unique name of an element of [[kind]].
  std::string element_name(const toml::table& table, const std::string& kind, size_t index,
                           std::map<std::string, int>& seen);

  // A rigid body (or the ground, when allowed) named by `key`.
  std::string rigid_reference(TableReader& in, const std::string& key, bool allow_ground);

  std::string rigid_list(bool with_ground) const;

  // A physical quantity outside the range any material or model has.
  static void check_range(TableReader& in, const char* key, double value, double lo, double hi, const std::string& unit);

  // Young's modulus and density of a material table, each in its range (flex_body_section.cpp).
  static void read_modulus_and_density(TableReader& in, double& youngs_modulus, double& density);

  // fracture_energy and critical_stretch of a material table (flex_body_section.cpp): both only
  // when both_allowed, one of them while fracture is on, each in its range.
  struct FractureKeys {
    std::optional<double> energy, stretch;
  };
  static FractureKeys read_fracture_keys(TableReader& in, bool fracture, bool both_allowed);

  // Two-body elements may not connect a body to itself.
  static void check_distinct(TableReader& in, const std::string& a, const std::string& b, const std::string& what);

  // ---------------------------------------------------------------------------
  // [scene], [solver], [solver.correction] and [limits] (solver_sections.cpp)

  void read_scene(const std::string& default_name);

  void read_solver();

  // Records where the value under `key` of `in` came from (file position or --set).
  void note_origin(TableReader& in, const char* key);

  // [limits]: budgets raised (or lowered) knowingly
  void read_limits();

  void read_correction(const toml::table& table);

  // ---------------------------------------------------------------------------
  // [[body]], [[joint]], [[driver]], [[force]], [[probe]] (mechanism_sections.cpp)

  BodyDef read_body(const toml::table& table, size_t index);

  JointDef read_joint(const toml::table& table, size_t index);

  DriverDef read_driver(const toml::table& table, size_t index);

  ForceDef read_force(const toml::table& table, size_t index);

  ProbeDef read_probe(const toml::table& table, size_t index);

  std::string all_body_list() const;

  // ---------------------------------------------------------------------------
  // [[flex_body]] with its notches, material and loads (flex_body_section.cpp)

  FlexBodyDef read_flex_body(const toml::table& table, size_t index);

  NotchDef read_notch(const toml::node& node, const std::string& key);

  PdMaterialDef read_material(const toml::table& table, const std::string& path, bool fracture);

  // [[flex_body.block_material]]: the material of one block of the body's point file
  BlockMaterialDef read_block_material(const toml::table& table, const std::string& path, const FlexBodyDef& flex);

  RegionLoadDef read_load(const toml::table& table, size_t index, const std::string& flex_name,
                          std::map<std::string, int>& names);

  // ---------------------------------------------------------------------------
  // [[attachment]] and [[contact]] (coupling_sections.cpp)

  AttachmentDef read_attachment(const toml::table& table, size_t index);

  // (the contact law is read in contact_reader.cpp)
  ContactDef read_contact(const toml::table& table, size_t index);

  const ReadContext& context_;
  TableReader top_;
  SceneDef scene_;
  std::set<std::string> rigid_names_, flex_names_;
  std::map<std::string, int> body_names_, joint_names_, driver_names_, force_names_, probe_names_, attachment_names_,
      contact_names_;
};

}  // namespace periflex
