#include "mbs/force_factory.h"

#include "core/error.h"
#include "mbs/applied_force.h"
#include "mbs/applied_torque.h"
#include "mbs/body_point.h"
#include "mbs/rotational_spring.h"
#include "mbs/spring_damper.h"

namespace periflex {

std::unique_ptr<ForceElement> make_force_element(const ForceDef& def, int body_i, int body_j,
                                                 const Eigen::VectorXd& q0) {
  const bool two_bodies = def.kind == ForceDef::Kind::kSpringDamper || def.kind == ForceDef::Kind::kRotationalSpring;
  if (two_bodies && body_i == body_j) {
    throw InputError(def.where, "force '" + def.name + "' connects a body to itself");
  }
  if (!two_bodies && body_i < 0) {
    throw InputError(def.where, "force '" + def.name + "' is applied to the ground; name a body in body_i");
  }
  if (def.stiffness < 0.0 || def.damping < 0.0) {
    throw InputError(def.where, "force '" + def.name + "' needs stiffness >= 0 and damping >= 0");
  }
  switch (def.kind) {
    case ForceDef::Kind::kSpringDamper: {
      const BodyPoint p_i{body_i, def.point_i}, p_j{body_j, def.point_j};
      const double free_length =
          def.free_length < 0.0 ? (p_j.position(q0) - p_i.position(q0)).norm() : def.free_length;
      return std::make_unique<SpringDamper>(def.name, p_i, p_j, def.stiffness, def.damping, free_length,
                                            def.actuator);
    }
    case ForceDef::Kind::kRotationalSpring: {
      const double a_i = body_i < 0 ? 0.0 : q0[3 * body_i + 2];
      const double a_j = body_j < 0 ? 0.0 : q0[3 * body_j + 2];
      const double free_angle = def.free_angle_from_initial ? a_j - a_i : def.free_angle;
      return std::make_unique<RotationalSpring>(def.name, body_i, body_j, def.stiffness, def.damping, free_angle);
    }
    case ForceDef::Kind::kForce:
      return std::make_unique<AppliedForce>(def.name, BodyPoint{body_i, def.point_i}, def.direction,
                                            def.magnitude);
    case ForceDef::Kind::kTorque:
      return std::make_unique<AppliedTorque>(def.name, body_i, def.magnitude);
  }
  throw InputError(def.where, "force '" + def.name + "' has an unknown type");
}

}  // namespace periflex
