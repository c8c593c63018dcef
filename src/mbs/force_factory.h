// Builds force elements from their definitions. Body indices are resolved (-1 = ground);
// q0 gives free lengths and angles marked "from initial". Throws InputError (def.where).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "mbs/force_element.h"
#include "scene/scene_def.h"

namespace periflex {

// body_j is used by the spring-damper and the rotational spring only.
std::unique_ptr<ForceElement> make_force_element(const ForceDef& def, int body_i, int body_j,
                                                 const Eigen::VectorXd& q0);

}  // namespace periflex
