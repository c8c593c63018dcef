#include "model/contact_assembly.h"

#include "contact/particle_contact.h"
#include "contact/rigid_contact.h"
#include "contact/rigid_particle_contact.h"
#include "model/system_model.h"

namespace periflex {

namespace {

// Particles of `flex` attached to rigid body `body` (they move with it and never touch it).
std::vector<int> attached_particles(const SystemModel& model, int body, const PdBody& flex) {
  std::vector<int> out;
  const int first = flex.coordinate_offset(), end = first + 2 * flex.particle_count();
  for (const Attachment& attachment : model.attachments) {
    const RigidFlexibleJoint& joint = *attachment.joint;
    if (joint.body() != body) continue;
    for (int c : joint.particle_coordinates()) {
      if (c >= first && c < end) out.push_back((c - first) / 2);
    }
  }
  return out;
}

}  // namespace

void build_contacts(const SceneDef& scene, SystemModel& model) {
  for (const ContactDef& def : scene.contacts) {
    if (def.kind == ContactDef::Kind::kRigidParticles) {
      const int body = model.body_index(def.body, def.where, "contact '" + def.name + "'");
      const PdBody& flex = *model.flex_bodies[model.flex_index(def.flex_bodies.front())];
      const BodyDef& rigid = model.bodies[body];
      model.contacts.push_back(std::make_unique<RigidParticleContact>(
          def, body, rigid.mass, rigid.shapes, flex, attached_particles(model, body, flex)));
    } else if (def.kind == ContactDef::Kind::kRigid) {
      const int body_i = model.body_index(def.body, def.where, "contact '" + def.name + "'");
      const int body_j = model.body_index(def.body_j, def.where, "contact '" + def.name + "'");
      model.contacts.push_back(
          std::make_unique<RigidContact>(def, body_i, model.bodies[body_i], body_j, model.bodies[body_j]));
    } else {
      std::vector<const PdBody*> bodies;
      for (const auto& name : def.flex_bodies) bodies.push_back(model.flex_bodies[model.flex_index(name)].get());
      model.contacts.push_back(std::make_unique<ParticleContact>(def, bodies));
    }
  }
}

}  // namespace periflex
