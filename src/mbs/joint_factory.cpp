#include "mbs/joint_factory.h"

#include "core/error.h"
#include "mbs/angle_driver.h"
#include "mbs/position_driver.h"
#include "mbs/revolute_joint.h"
#include "mbs/revolute_revolute_joint.h"
#include "mbs/revolute_translational_joint.h"
#include "mbs/rigid_joint.h"
#include "mbs/translational_joint.h"

namespace periflex {

static double angle_of(const Eigen::VectorXd& q, int body) { return body < 0 ? 0.0 : q[3 * body + 2]; }

std::unique_ptr<Constraint> make_joint(const JointDef& def, int body_i, int body_j, const Eigen::VectorXd& q0) {
  // a joint needs two different bodies, at most one of them the ground
  if (body_i == body_j) {
    throw InputError(def.where, "joint '" + def.name + "' connects a body to itself");
  }
  const BodyPoint p_i{body_i, def.point_i}, p_j{body_j, def.point_j};
  const double initial_relative = angle_of(q0, body_j) - angle_of(q0, body_i);
  const bool needs_axis = def.kind == JointDef::Kind::kTranslational ||
                          def.kind == JointDef::Kind::kRevoluteTranslational;
  if (needs_axis && def.axis_i.norm() == 0.0) {
    throw InputError(def.where, "joint '" + def.name + "' needs a non-zero axis_i");
  }
  switch (def.kind) {
    case JointDef::Kind::kRevolute:
      return std::make_unique<RevoluteJoint>(def.name, p_i, p_j);
    case JointDef::Kind::kTranslational:
      return std::make_unique<TranslationalJoint>(def.name, p_i, p_j, def.axis_i, initial_relative);
    case JointDef::Kind::kRigid: {
      const double angle = def.relative_angle_from_initial ? initial_relative : def.relative_angle;
      return std::make_unique<RigidJoint>(def.name, p_i, p_j, angle);
    }
    case JointDef::Kind::kRevoluteRevolute: {
      // the link length comes from the definition or from the initial distance of the points
      double length = def.length;
      if (def.length_from_initial || length <= 0.0) length = (p_j.position(q0) - p_i.position(q0)).norm();
      if (!(length > 0.0)) {
        throw InputError(def.where, "joint '" + def.name +
                                        "' (revolute_revolute) has zero length; give 'length' > 0 or "
                                        "separate its points");
      }
      return std::make_unique<RevoluteRevoluteJoint>(def.name, p_i, p_j, length);
    }
    case JointDef::Kind::kRevoluteTranslational:
      return std::make_unique<RevoluteTranslationalJoint>(def.name, p_i, p_j, def.axis_i, def.offset);
  }
  throw InputError(def.where, "joint '" + def.name + "' has an unknown type");
}

std::unique_ptr<Constraint> make_driver(const DriverDef& def, int body_i, int body_j, const Eigen::VectorXd&) {
  const bool relative = def.kind == DriverDef::Kind::kRelativeAngle ||
                        def.kind == DriverDef::Kind::kRelativePosition;
  if (body_i < 0 && !relative) {
    throw InputError(def.where, "driver '" + def.name + "' must drive a body, not the ground");
  }
  if (relative && body_i == body_j) {
    throw InputError(def.where, "driver '" + def.name + "' relates a body to itself");
  }
  const bool positional = def.kind == DriverDef::Kind::kAbsolutePosition ||
                          def.kind == DriverDef::Kind::kRelativePosition;
  if (positional && def.axis.norm() == 0.0) {
    throw InputError(def.where, "driver '" + def.name + "' needs a non-zero axis");
  }
  switch (def.kind) {
    case DriverDef::Kind::kAbsoluteAngle:
      return std::make_unique<AngleDriver>(def.name, body_i, -1, def.function);
    case DriverDef::Kind::kRelativeAngle:
      return std::make_unique<AngleDriver>(def.name, body_j, body_i, def.function);
    case DriverDef::Kind::kAbsolutePosition: {
      // measured from the global origin along a global axis
      const AxisGap gap{BodyPoint{-1, Vec2::Zero()}, BodyPoint{body_i, def.point_i}, def.axis};
      return std::make_unique<PositionDriver>(def.name, gap, def.function);
    }
    case DriverDef::Kind::kRelativePosition: {
      const AxisGap gap{BodyPoint{body_i, def.point_i}, BodyPoint{body_j, def.point_j}, def.axis};
      return std::make_unique<PositionDriver>(def.name, gap, def.function);
    }
  }
  throw InputError(def.where, "driver '" + def.name + "' has an unknown type");
}

}  // namespace periflex
