// The assembled model: what a SceneDef declares, turned into state vectors and the lists of
// constraint blocks and force elements the stepper works on. Built once per Simulation, from the
// parts the layers below make (mbs: joints, drivers, forces; pd: flexible bodies; coupling:
// rigid-flexible joints; contact: contact elements); the stepper (src/solve) reads it.
//
// Coordinates: rigid body k owns q[3k .. 3k+2] = x, y, phi; the particles of the flexible
// bodies follow, two each, one contiguous slice per flexible body.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_element.h"
#include "coupling/rigid_flexible_joint.h"
#include "mbs/body_point.h"
#include "mbs/constraint.h"
#include "mbs/force_element.h"
#include "model/marker_kind.h"
#include "pd/pd_body.h"
#include "scene/scene_def.h"

namespace periflex {

// One block of constraint rows and where it came from.
struct ConstraintBlock {
  std::unique_ptr<Constraint> constraint;
  int first_row = 0;
  enum class Origin { kJoint, kDriver, kAttachment } origin = Origin::kJoint;
  SourceLocation where;  // the scene entry it came from
};

// A point written to series.csv: a body-fixed point of a rigid body, or one particle.
struct ProbePoint {
  std::string name;
  BodyPoint point;               // rigid probe (body >= 0)
  int particle_coordinate = -1;  // particle probe: index of x in q
  int particle = -1;             // particle probe: index among all flexible bodies' particles
  bool is_particle() const { return particle_coordinate >= 0; }
};

// A drawn marker: one point (pins, welds, drivers, attachments) or two (links, sliders).
struct MarkerSource {
  MarkerKind kind = MarkerKind::kRevolute;
  BodyPoint a, b;
};

// A rigid-flexible joint of the model, typed: the joint and its block in
// SystemModel::constraints, which owns it.
struct Attachment {
  const RigidFlexibleJoint* joint = nullptr;
  int block = 0;      // index into SystemModel::constraints
  int first_row = 0;  // its first constraint row (two rows per particle follow)
};

struct SystemModel {
  Vec2 gravity = Vec2::Zero();
  std::vector<BodyDef> bodies;           // rigid bodies in coordinate order (ground excluded)
  int rigid_coordinates = 0;
  int coordinate_count = 0;

  Eigen::VectorXd mass;                  // lumped diagonal mass per coordinate (m, m, J; rho V)
  Eigen::VectorXd gravity_force;         // mass * gravity on every translational coordinate
  Eigen::VectorXd q0, qd0;               // initial state as declared (before projection)

  std::vector<ConstraintBlock> constraints;
  int constraint_rows = 0;
  // the rigid-flexible joints among the constraints (their blocks' origin is kAttachment), in
  // constraint order
  std::vector<Attachment> attachments;
  std::vector<std::unique_ptr<ForceElement>> forces;  // springs, dampers, applied loads
  std::vector<MarkerSource> spring_lines;             // spring-dampers, for drawing

  std::vector<std::unique_ptr<PdBody>> flex_bodies;
  std::vector<PrescribedCoordinate> prescribed;
  std::vector<char> is_prescribed;       // per coordinate

  // contacts of [[contact]] (src/contact/); empty, and never visited, without them
  std::vector<std::unique_ptr<ContactElement>> contacts;

  std::vector<ProbePoint> probes;
  std::vector<MarkerSource> markers;

  int joints = 0, drivers = 0;
  double length_scale = 1.0;             // size of the initial configuration

  // Index of a rigid body by name; -1 for "ground". Throws InputError (at `where`) when unknown.
  int body_index(const std::string& name, const SourceLocation& where, const std::string& what) const;
  // Index of a flexible body by name, or -1.
  int flex_index(const std::string& name) const;
  // Human-readable owner of a coordinate: "body 'crank'" or "flexible body 'plate'".
  std::string coordinate_owner(int coordinate) const;
};

// Builds the rigid part (bodies, joints, drivers, force elements, rigid probes), then the
// flexible part and attachments (build_flexible_part), then finalises masses and gravity.
// Throws InputError on an impossible scene.
std::unique_ptr<SystemModel> build_system_model(const SceneDef& scene);

// Peridynamic bodies, their prescribed coordinates, particle probes and rigid-flexible joints.
// Kept apart so the rigid assembly does not depend on the peridynamics.
void build_flexible_part(const SceneDef& scene, SystemModel& model);

}  // namespace periflex
