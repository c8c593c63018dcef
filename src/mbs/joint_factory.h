// Builds the constraint blocks of joints and drivers from their definitions. Body indices are
// already resolved (-1 = ground); q0 is the initial configuration, from which lengths and
// angles marked "from initial" are taken. Impossible definitions throw InputError (def.where).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "mbs/constraint.h"
#include "scene/scene_def.h"

namespace periflex {

std::unique_ptr<Constraint> make_joint(const JointDef& def, int body_i, int body_j, const Eigen::VectorXd& q0);

// body_j is used by the relative drivers only.
std::unique_ptr<Constraint> make_driver(const DriverDef& def, int body_i, int body_j, const Eigen::VectorXd& q0);

}  // namespace periflex
