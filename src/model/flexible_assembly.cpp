// The flexible part of the model: peridynamic bodies (their particles appended to q after the
// rigid coordinates), their imposed motions, particle probes and the rigid-flexible joints.
#include <numeric>

#include "core/error.h"
#include "pd/bond_force_device.h"
#include "model/system_model.h"

namespace periflex {

namespace {

// A body's bonds on the GPU: refused (InputError at the body) when its law cannot run there or no
// device can be made here, naming what is missing.
void attach_bond_force_device(const FlexBodyDef& def, DevicePrecision precision, PdBody& flex) {
  try {
    flex.use_bond_force_device(make_bond_force_device(precision));
  } catch (const std::exception& e) {
    throw InputError(def.where, std::string("solver.device = \"gpu\": ") + e.what() +
                                    "; run it on the CPU (--device cpu)");
  }
}

// The particles an attachment holds: those in its region, and with pixels = "blue" only the grip
// particles of the body's picture (all of them when no region is given).
std::vector<int> held_particles(const AttachmentDef& def, const SceneDef& scene, const PdBody& flex) {
  if (def.pixels.empty()) return flex.particles_in(def.region);
  std::vector<uint8_t> grip;
  for (const FlexBodyDef& body : scene.flex_bodies)
    if (body.name == def.flex_body && body.particles) grip = body.particles->grip;
  std::vector<int> candidates;
  if (def.region.kind == ShapeDef::Kind::kNone) {
    candidates.resize(static_cast<size_t>(flex.particle_count()));
    std::iota(candidates.begin(), candidates.end(), 0);
  } else {
    candidates = flex.particles_in(def.region);
  }
  std::vector<int> held;
  for (int p : candidates)
    if (static_cast<size_t>(p) < grip.size() && grip[p]) held.push_back(p);
  return held;
}

}  // namespace

void build_flexible_part(const SceneDef& scene, SystemModel& m) {
  // each flexible body takes the next contiguous slice of q
  for (const auto& def : scene.flex_bodies) {
    for (const auto& body : m.bodies) {
      if (body.name == def.name) throw InputError(def.where, "a rigid body is also named '" + def.name + "'");
    }
    if (m.flex_index(def.name) >= 0) throw InputError(def.where, "two flexible bodies are named '" + def.name + "'");
    const int offset = static_cast<int>(m.q0.size());
    auto flex = PdBody::build(def, offset);
    // the bond forces on the device the solver names (pd/bond_force_device.h)
    if (scene.solver.device == "gpu")
      attach_bond_force_device(def, device_precision(scene.solver.precision), *flex);
    const int n = 2 * flex->particle_count();
    const auto& reference = flex->reference_positions();
    const auto velocities = flex->initial_velocities();
    m.q0.conservativeResize(offset + n);
    m.qd0.conservativeResize(offset + n);
    for (int k = 0; k < n; ++k) {
      m.q0[offset + k] = reference[k];
      m.qd0[offset + k] = velocities[k];
    }
    for (const auto& p : flex->prescribed_coordinates()) m.prescribed.push_back(p);
    m.flex_bodies.push_back(std::move(flex));
  }

  // particle probes: the particle nearest to the reference point
  for (const auto& def : scene.probes) {
    const int f = m.flex_index(def.body);
    if (f < 0) continue;
    const PdBody& flex = *m.flex_bodies[f];
    ProbePoint p;
    p.name = def.name;
    const int nearest = flex.nearest_particle(def.point);
    p.particle_coordinate = flex.coordinate_offset() + 2 * nearest;
    p.particle = nearest;
    for (int before = 0; before < f; ++before) p.particle += m.flex_bodies[before]->particle_count();
    m.probes.push_back(p);
  }

  // attachments: every particle of the region follows the rigid body
  for (const auto& def : scene.attachments) {
    const int f = m.flex_index(def.flex_body);
    if (f < 0) throw InputError(def.where, "attachment '" + def.name + "' names an unknown flexible body '" +
                                               def.flex_body + "'");
    const int body = m.body_index(def.body, def.where, "attachment '" + def.name + "'");
    const PdBody& flex = *m.flex_bodies[f];
    std::vector<int> coordinates;
    for (int p : held_particles(def, scene, flex)) coordinates.push_back(flex.coordinate_offset() + 2 * p);
    if (coordinates.empty()) {
      throw InputError(def.where, "attachment '" + def.name + "' holds no particle of '" + def.flex_body + "'; " +
                                      (def.pixels.empty() ? "enlarge its region"
                                                          : "no " + def.pixels + " pixel of its picture lies in its region"));
    }
    auto joint = make_rigid_flexible_joint(def.name, body, coordinates, m.q0);
    // drawn at the centroid of the attached particles, carried by the body
    Vec2 centroid = Vec2::Zero();
    for (int k = 0; k < joint->particle_count(); ++k) centroid += joint->local_position(k);
    centroid /= joint->particle_count();
    MarkerSource marker;
    marker.kind = MarkerKind::kAttachment;
    marker.a = marker.b = BodyPoint{body, centroid};
    m.markers.push_back(marker);

    // the joint joins the constraints, and the typed list of attachments points at it
    m.attachments.push_back(Attachment{joint.get(), static_cast<int>(m.constraints.size()), m.constraint_rows});
    ConstraintBlock block;
    block.first_row = m.constraint_rows;
    block.origin = ConstraintBlock::Origin::kAttachment;
    block.where = def.where;
    m.constraint_rows += joint->rows();
    block.constraint = std::move(joint);
    m.constraints.push_back(std::move(block));
  }
}

}  // namespace periflex
