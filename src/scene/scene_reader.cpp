// A scene's TOML tree to a validated SceneDef (scene_reader.h): the sections in the order that lets
// references resolve as they are read, the element lists of arrays of tables, names unique per
// kind, references to rigid bodies, and the range checks the sections share.
#include "scene/scene_reader.h"

#include <algorithm>

#include "scene/scene_table_reader.h"

namespace periflex {

namespace {

using scene_tables::join;

}  // namespace

SceneDef SceneTableReader::read(const std::string& default_name) {
  // the model sections first, so that references can be resolved as they are read
  read_scene(default_name);
  read_solver();
  read_limits();
  for (const auto& [table, index] : elements("body")) scene_.bodies.push_back(read_body(*table, index));
  for (const auto& [table, index] : elements("flex_body")) scene_.flex_bodies.push_back(read_flex_body(*table, index));
  for (const auto& [table, index] : elements("joint")) scene_.joints.push_back(read_joint(*table, index));
  for (const auto& [table, index] : elements("driver")) scene_.drivers.push_back(read_driver(*table, index));
  for (const auto& [table, index] : elements("force")) scene_.forces.push_back(read_force(*table, index));
  for (const auto& [table, index] : elements("probe")) scene_.probes.push_back(read_probe(*table, index));
  for (const auto& [table, index] : elements("attachment"))
    scene_.attachments.push_back(read_attachment(*table, index));
  for (const auto& [table, index] : elements("contact")) scene_.contacts.push_back(read_contact(*table, index));
  top_.finish();

  // a scene needs something that moves
  if (scene_.bodies.empty() && scene_.flex_bodies.empty()) {
    SourceLocation where = context_.locate(nullptr, "body");
    where.line = 1;
    throw InputError(where, "the scene declares no [[body]] and no [[flex_body]]; a scene needs at least one");
  }
  return scene_;
}

// The tables of the array of tables `key` (e.g. every [[body]]), with their indices.
std::vector<std::pair<const toml::table*, size_t>> SceneTableReader::elements(const std::string& key) {
  std::vector<std::pair<const toml::table*, size_t>> out;
  const toml::node* node = top_.node(key);
  if (node == nullptr) return out;
  const auto* array = node->as_array();
  if (array == nullptr)
    context_.fail(node, key, "expected [[" + key + "]] (an array of tables), found " + describe_type(*node));
  for (size_t k = 0; k < array->size(); ++k) {
    const toml::node* element = array->get(k);
    if (!element->is_table())
      context_.fail(element, key, "expected [[" + key + "]] tables, found " + describe_type(*element));
    out.emplace_back(element->as_table(), k);
  }
  return out;
}

// The required, well-formed, per-kind unique name of an element of [[kind]].
std::string SceneTableReader::element_name(const toml::table& table, const std::string& kind, size_t index,
                         std::map<std::string, int>& seen) {
  const std::string path = kind + "." + std::to_string(index);
  const toml::node* node = table.get("name");
  if (node == nullptr)
    context_.fail(&table, path + ".name", "missing required key 'name' in [[" + kind + "]] number " +
                  std::to_string(index + 1));
  const auto* text = node->as_string();
  if (text == nullptr) context_.fail(node, path + ".name", "expected a string, found " + describe_type(*node));
  const std::string name = text->get();
  // names appear in override paths and output columns: no dots, no spaces
  const bool plain = !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
    return c == '.' || c == '=' || c == '"' || c == ',' || static_cast<unsigned char>(c) <= ' ';
  });
  if (!plain)
    context_.fail(node, path + ".name", "name '" + name + "' must be non-empty without dots, '=', quotes, commas or spaces");
  const auto first = seen.find(name);
  if (first != seen.end())
    context_.fail(node, kind + "." + name + ".name",
                  "duplicate name '" + name + "' (already declared at line " + std::to_string(first->second) + ")");
  seen.emplace(name, static_cast<int>(node->source().begin.line));
  return name;
}

// A rigid body (or the ground, when allowed) named by `key`.
std::string SceneTableReader::rigid_reference(TableReader& in, const std::string& key, bool allow_ground) {
  const std::string name = in.required_string(key);
  if (name == "ground") {
    if (!allow_ground) in.fail(key, "'ground' cannot be used here: it does not move; name a rigid body");
    return name;
  }
  if (rigid_names_.count(name) != 0) return name;
  if (flex_names_.count(name) != 0)
    in.fail(key, "'" + name + "' is a flexible body; " + key + " must name a rigid body" +
            " (couple a flexible body through an [[attachment]] to a virtual body)");
  const std::string rigid = rigid_list(allow_ground);
  std::string flexible;
  for (const FlexBodyDef& flex : scene_.flex_bodies) flexible += (flexible.empty() ? "" : ", ") + flex.name;
  in.fail(key, "body '" + name + "' is not declared (rigid bodies: " + (rigid.empty() ? std::string("none") : rigid) +
          (flexible.empty() ? std::string() : "; flexible bodies: " + flexible) + ")");
}

std::string SceneTableReader::rigid_list(bool with_ground) const {
  std::vector<std::string> names;
  if (with_ground) names.emplace_back("ground");
  for (const BodyDef& body : scene_.bodies) names.push_back(body.name);
  return join(names);
}

// A physical quantity outside the range any material or model has.
void SceneTableReader::check_range(TableReader& in, const char* key, double value, double lo, double hi, const std::string& unit) {
  if (value >= lo && value <= hi) return;
  const std::string u = unit.empty() ? "" : " " + unit;
  in.fail(key, std::string(key) + " = " + format_number(value) + u + " is outside the physically meaningful range [" +
          format_number(lo) + ", " + format_number(hi) + "]" + u);
}

// Two-body elements may not connect a body to itself.
void SceneTableReader::check_distinct(TableReader& in, const std::string& a, const std::string& b, const std::string& what) {
  if (a == b) in.fail("body_j", what + " connects '" + a + "' to itself; body_i and body_j must differ");
}

SceneDef read_scene_tables(const toml::table& root, const ReadContext& context, const std::string& default_name) {
  SceneTableReader reader(context, root);
  return reader.read(default_name);
}

}  // namespace periflex
