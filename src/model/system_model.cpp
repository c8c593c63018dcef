#include "model/system_model.h"

#include <algorithm>
#include <cmath>

#include "model/contact_assembly.h"
#include "core/error.h"
#include "mbs/force_factory.h"
#include "mbs/joint_factory.h"
#include "mbs/revolute_revolute_joint.h"
#include "mbs/revolute_translational_joint.h"
#include "mbs/spring_damper.h"
#include "mbs/translational_joint.h"

namespace periflex {

int SystemModel::body_index(const std::string& name, const SourceLocation& where, const std::string& what) const {
  if (name == "ground") return -1;
  for (size_t k = 0; k < bodies.size(); ++k) {
    if (bodies[k].name == name) return static_cast<int>(k);
  }
  throw InputError(where, what + " names an unknown body '" + name + "'");
}

int SystemModel::flex_index(const std::string& name) const {
  for (size_t k = 0; k < flex_bodies.size(); ++k) {
    if (flex_bodies[k]->name() == name) return static_cast<int>(k);
  }
  return -1;
}

std::string SystemModel::coordinate_owner(int coordinate) const {
  if (coordinate < rigid_coordinates) return "body '" + bodies[coordinate / 3].name + "'";
  for (const auto& flex : flex_bodies) {
    const int first = flex->coordinate_offset();
    if (coordinate >= first && coordinate < first + 2 * flex->particle_count()) {
      return "particle " + std::to_string((coordinate - first) / 2) + " of flexible body '" + flex->name() + "'";
    }
  }
  return "coordinate " + std::to_string(coordinate);
}

// Marker points of a joint, for drawing.
static MarkerSource joint_marker(const JointDef& def, int bi, int bj) {
  MarkerSource m;
  m.a = BodyPoint{bi, def.point_i};
  m.b = BodyPoint{bj, def.point_j};
  switch (def.kind) {
    case JointDef::Kind::kRevolute: m.kind = MarkerKind::kRevolute; break;
    case JointDef::Kind::kRigid: m.kind = MarkerKind::kRigid; break;
    case JointDef::Kind::kRevoluteRevolute: m.kind = MarkerKind::kLink; break;
    case JointDef::Kind::kTranslational:
    case JointDef::Kind::kRevoluteTranslational: m.kind = MarkerKind::kTranslational; break;
  }
  return m;
}

std::unique_ptr<SystemModel> build_system_model(const SceneDef& scene) {
  auto model = std::make_unique<SystemModel>();
  SystemModel& m = *model;
  m.gravity = scene.gravity;

  // rigid bodies: names unique, masses and inertias not negative
  for (const auto& body : scene.bodies) {
    if (body.name == "ground" || body.ground) {
      throw InputError(body.where, "the ground is implicit; do not declare a body named 'ground'");
    }
    for (const auto& other : m.bodies) {
      if (other.name == body.name) throw InputError(body.where, "two bodies are named '" + body.name + "'");
    }
    if (!(body.mass >= 0.0) || !(body.inertia >= 0.0)) {
      throw InputError(body.where, "body '" + body.name + "' needs mass >= 0 and inertia >= 0");
    }
    m.bodies.push_back(body);
  }
  const int nb = static_cast<int>(m.bodies.size());
  m.rigid_coordinates = 3 * nb;
  m.q0 = Eigen::VectorXd::Zero(m.rigid_coordinates);
  m.qd0 = Eigen::VectorXd::Zero(m.rigid_coordinates);
  for (int k = 0; k < nb; ++k) {
    const BodyDef& b = m.bodies[k];
    m.q0.segment<3>(3 * k) << b.position.x(), b.position.y(), b.angle;
    m.qd0.segment<3>(3 * k) << b.velocity.x(), b.velocity.y(), b.angular_velocity;
  }

  // joints, then drivers, each a block of rows
  auto add_block = [&](std::unique_ptr<Constraint> c, ConstraintBlock::Origin origin, const SourceLocation& where) {
    ConstraintBlock block;
    block.first_row = m.constraint_rows;
    block.origin = origin;
    block.where = where;
    m.constraint_rows += c->rows();
    block.constraint = std::move(c);
    m.constraints.push_back(std::move(block));
  };
  for (const auto& def : scene.joints) {
    const int bi = m.body_index(def.body_i, def.where, "joint '" + def.name + "'");
    const int bj = m.body_index(def.body_j, def.where, "joint '" + def.name + "'");
    add_block(make_joint(def, bi, bj, m.q0), ConstraintBlock::Origin::kJoint, def.where);
    m.markers.push_back(joint_marker(def, bi, bj));
    ++m.joints;
  }
  for (const auto& def : scene.drivers) {
    const int bi = m.body_index(def.body_i, def.where, "driver '" + def.name + "'");
    const bool relative =
        def.kind == DriverDef::Kind::kRelativeAngle || def.kind == DriverDef::Kind::kRelativePosition;
    const int bj = relative ? m.body_index(def.body_j, def.where, "driver '" + def.name + "'") : -1;
    add_block(make_driver(def, bi, bj, m.q0), ConstraintBlock::Origin::kDriver, def.where);
    MarkerSource marker;
    marker.kind = MarkerKind::kDriver;
    marker.a = BodyPoint{bi, def.point_i};
    marker.b = marker.a;
    m.markers.push_back(marker);
    ++m.drivers;
  }

  // force elements
  for (const auto& def : scene.forces) {
    const int bi = m.body_index(def.body_i, def.where, "force '" + def.name + "'");
    const bool two = def.kind == ForceDef::Kind::kSpringDamper || def.kind == ForceDef::Kind::kRotationalSpring;
    const int bj = two ? m.body_index(def.body_j, def.where, "force '" + def.name + "'") : -1;
    m.forces.push_back(make_force_element(def, bi, bj, m.q0));
    if (def.kind == ForceDef::Kind::kSpringDamper) {
      m.spring_lines.push_back(MarkerSource{MarkerKind::kLink, BodyPoint{bi, def.point_i},
                                            BodyPoint{bj, def.point_j}});
    }
  }

  // the flexible part appends particle coordinates, loads and attachments
  build_flexible_part(scene, m);
  m.coordinate_count = static_cast<int>(m.q0.size());

  // rigid probes (particle probes were resolved with the flexible bodies)
  for (const auto& def : scene.probes) {
    if (m.flex_index(def.body) >= 0) continue;
    ProbePoint p;
    p.name = def.name;
    p.point = BodyPoint{m.body_index(def.body, def.where, "probe '" + def.name + "'"), def.point};
    m.probes.push_back(p);
  }

  // lumped masses and gravity on every translational coordinate
  m.mass = Eigen::VectorXd::Zero(m.coordinate_count);
  m.gravity_force = Eigen::VectorXd::Zero(m.coordinate_count);
  for (int k = 0; k < nb; ++k) {
    m.mass.segment<3>(3 * k) << m.bodies[k].mass, m.bodies[k].mass, m.bodies[k].inertia;
  }
  for (const auto& flex : m.flex_bodies) {
    const auto& pm = flex->masses();
    for (int p = 0; p < flex->particle_count(); ++p) {
      m.mass[flex->coordinate_offset() + 2 * p] = pm[p];
      m.mass[flex->coordinate_offset() + 2 * p + 1] = pm[p];
    }
  }
  for (int c = 0; c < m.coordinate_count; ++c) {
    const bool translational = c >= m.rigid_coordinates || c % 3 != 2;
    if (translational) m.gravity_force[c] = m.mass[c] * m.gravity[(c < m.rigid_coordinates ? c % 3 : (c - m.rigid_coordinates) % 2)];
  }
  m.is_prescribed.assign(m.coordinate_count, 0);
  for (const auto& p : m.prescribed) m.is_prescribed[p.coordinate] = 1;

  // contacts, once bodies, particles and attachments exist
  build_contacts(scene, m);

  // size of the initial configuration: bounding box of body origins, joint points and particles
  Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
  auto grow = [&](const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  grow(Vec2::Zero());
  for (int k = 0; k < nb; ++k) grow(m.q0.segment<2>(3 * k));
  for (const auto& marker : m.markers) {
    grow(marker.a.position(m.q0));
    grow(marker.b.position(m.q0));
  }
  for (int c = m.rigid_coordinates; c + 1 < m.coordinate_count; c += 2) grow(m.q0.segment<2>(c));
  m.length_scale = std::max((hi - lo).norm(), 1e-3);
  return model;
}

}  // namespace periflex
