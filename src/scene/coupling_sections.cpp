// What joins bodies of different kinds or lets them touch: [[attachment]] (a flexible body's
// particles held by a rigid body) and [[contact]] (the law is read in contact_reader.cpp).
#include "scene/scene_table_reader.h"

#include <algorithm>
#include <utility>

#include "scene/contact_reader.h"
#include "scene/shape_reader.h"

namespace periflex {

namespace {

using scene_tables::join;

}  // namespace

AttachmentDef SceneTableReader::read_attachment(const toml::table& table, size_t index) {
  AttachmentDef attachment;
  attachment.name = element_name(table, "attachment", index, attachment_names_);
  TableReader in(context_, table, "attachment." + attachment.name, "[[attachment]] '" + attachment.name + "'");
  in.node("name");
  attachment.where = in.where();
  attachment.body = rigid_reference(in, "body", false);
  attachment.flex_body = in.required_string("flex_body");
  if (flex_names_.count(attachment.flex_body) == 0) {
    std::vector<std::string> names;
    for (const FlexBodyDef& flex : scene_.flex_bodies) names.push_back(flex.name);
    in.fail("flex_body", "flexible body '" + attachment.flex_body + "' is not declared (flexible bodies: " +
            (names.empty() ? std::string("none") : join(names)) + ")");
  }
  // the particles a picture marks blue, within the region when one is given
  if (in.has("pixels")) attachment.pixels = in.choice("pixels", {"blue"}, "blue");
  if (!attachment.pixels.empty()) {
    const FlexBodyDef* flex = nullptr;
    for (const FlexBodyDef& f : scene_.flex_bodies)
      if (f.name == attachment.flex_body) flex = &f;
    if (flex == nullptr || !flex->particles || flex->particles->grip.empty())
      in.fail("pixels", "flexible body '" + attachment.flex_body +
                            "' is not read from a picture (shape type \"image\"), so no pixel of it is blue");
  }
  const toml::node* region = in.node("region");
  if (region == nullptr && attachment.pixels.empty()) in.fail_missing("region");
  if (region != nullptr) attachment.region = read_shape(context_, *region, in.key_path("region"), kRegionShapeKinds);
  in.finish();
  return attachment;
}

ContactDef SceneTableReader::read_contact(const toml::table& table, size_t index) {
  ContactDef contact;
  contact.name = element_name(table, "contact", index, contact_names_);
  TableReader in(context_, table, "contact." + contact.name, "[[contact]] '" + contact.name + "'");
  in.node("name");
  contact.where = in.where();
  contact.kind = read_contact_kind(in);
  if (contact.kind == ContactDef::Kind::kRigidParticles) {
    // the rigid body's drawing shapes are its contact shapes
    contact.body = rigid_reference(in, "body", false);
    const auto body = std::find_if(scene_.bodies.begin(), scene_.bodies.end(),
                                   [&](const BodyDef& b) { return b.name == contact.body; });
    if (body->shapes.empty())
      in.fail("body", "body '" + contact.body + "' has no shape to touch; give it a shape (its drawing shape is "
                      "its contact shape)");
  }
  if (contact.kind == ContactDef::Kind::kRigid) {
    // two rigid bodies, each with a shape
    contact.body = rigid_reference(in, "body_i", false);
    contact.body_j = rigid_reference(in, "body_j", false);
    if (contact.body_j == contact.body) in.fail("body_j", "body_j must differ from body_i ('" + contact.body + "')");
    for (const auto& [key, name] : {std::pair<const char*, std::string>{"body_i", contact.body}, {"body_j", contact.body_j}}) {
      const auto body = std::find_if(scene_.bodies.begin(), scene_.bodies.end(),
                                     [&](const BodyDef& b) { return b.name == name; });
      if (body->shapes.empty())
        in.fail(key, "body '" + name + "' has no shape to touch; give it a shape (its drawing shape is its "
                     "contact shape)");
    }
  }
  read_contact_law(in, flex_names_, contact);
  return contact;
}

}  // namespace periflex
