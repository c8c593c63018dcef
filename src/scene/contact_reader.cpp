#include "scene/contact_reader.h"

#include <algorithm>

namespace periflex {

const std::set<std::string> kContactKeys = {"name",     "type",           "body",           "flex_body",
                                            "flex_bodies", "stiffness",   "restitution",    "friction",
                                            "friction_velocity", "margin", "distance_ratio", "skin_ratio",
                                            "body_i",   "body_j"};

namespace {

std::string flex_list(const std::set<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? std::string("none") : out;
}

// A declared flexible body named by the string node `node` (dotted key `key`).
std::string flex_reference(TableReader& in, const toml::node& node, const std::string& key,
                           const std::set<std::string>& flex_names) {
  const auto* text = node.as_string();
  if (text == nullptr) in.context().fail(&node, key, "expected a string, found " + describe_type(node));
  const std::string name = text->get();
  if (flex_names.count(name) == 0)
    in.context().fail(&node, key, "flexible body '" + name + "' is not declared (flexible bodies: " +
                                      flex_list(flex_names) + ")");
  return name;
}

}  // namespace

ContactDef::Kind read_contact_kind(TableReader& in) {
  const std::string type = in.required_choice("type", {"rigid_particles", "particles", "rigid"});
  if (type == "rigid") return ContactDef::Kind::kRigid;
  return type == "particles" ? ContactDef::Kind::kParticles : ContactDef::Kind::kRigidParticles;
}

void read_contact_law(TableReader& in, const std::set<std::string>& flex_names, ContactDef& contact) {
  const bool rigid = contact.kind == ContactDef::Kind::kRigidParticles;
  const bool two_rigid = contact.kind == ContactDef::Kind::kRigid;
  // the bodies: one flexible body against a rigid one, or a list of flexible bodies (two rigid
  // bodies are read with the other references)
  if (two_rigid) {
    // no particles: no material to take a stiffness from
    if (!in.has("stiffness"))
      in.fail_missing("stiffness", "the penalty stiffness [N/m] of each contact point (two rigid bodies have no "
                                   "material to take it from)");
  } else if (rigid) {
    const toml::node* node = in.node("flex_body");
    if (node == nullptr) in.fail_missing("flex_body", "the flexible body the rigid body touches");
    contact.flex_bodies = {flex_reference(in, *node, in.key_path("flex_body"), flex_names)};
  } else {
    const toml::node* node = in.node("flex_bodies");
    if (node == nullptr) in.fail_missing("flex_bodies", "the flexible bodies whose particles touch");
    const auto* list = node->as_array();
    if (list == nullptr || list->empty())
      in.fail("flex_bodies", "expected a non-empty array of flexible body names, found " + describe_type(*node));
    for (size_t k = 0; k < list->size(); ++k) {
      const std::string key = in.key_path("flex_bodies") + "[" + std::to_string(k) + "]";
      const std::string name = flex_reference(in, *list->get(k), key, flex_names);
      if (std::find(contact.flex_bodies.begin(), contact.flex_bodies.end(), name) != contact.flex_bodies.end())
        in.context().fail(list->get(k), key, "flexible body '" + name + "' is listed twice");
      contact.flex_bodies.push_back(name);
    }
  }

  // the law: penalty stiffness (0: from the micromodulus), restitution, friction
  contact.stiffness = in.number("stiffness", 0.0, Sign::kPositive);
  if (in.has("stiffness")) contact.stiffness_where = in.context().locate(in.node("stiffness"), in.key_path("stiffness"));
  contact.restitution = in.number("restitution", contact.restitution, Sign::kPositive);
  if (contact.restitution > 1.0)
    in.fail("restitution", "restitution must be in (0, 1] (1: no damping), found " +
                               format_number(contact.restitution));
  if (rigid || two_rigid) {
    contact.friction = in.number("friction", contact.friction, Sign::kNonNegative);
    contact.friction_velocity = in.number("friction_velocity", contact.friction_velocity, Sign::kPositive);
    if (rigid) contact.margin = in.number("margin", contact.margin, Sign::kNonNegative, true);
  } else {
    contact.distance_ratio = in.number("distance_ratio", contact.distance_ratio, Sign::kPositive);
    if (contact.distance_ratio > 1.0)
      in.fail("distance_ratio", "distance_ratio must be in (0, 1] (a fraction of the grid spacing; bonded "
                                "neighbours sit one spacing apart), found " + format_number(contact.distance_ratio));
    contact.skin_ratio = in.number("skin_ratio", contact.skin_ratio, Sign::kPositive);
    if (contact.skin_ratio > 5.0)
      in.fail("skin_ratio", "skin_ratio must be in (0, 5] grid spacings, found " + format_number(contact.skin_ratio));
  }
  in.finish(kContactKeys,
            std::string("a ") + (two_rigid ? "rigid" : rigid ? "rigid_particles" : "particles") + " contact");
}

}  // namespace periflex
