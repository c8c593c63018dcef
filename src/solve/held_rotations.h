// Rotations no equation of motion can determine, held at their initial angle.
//
// A body with zero inertia whose every constraint point lies at its own origin (a point mass on a
// pin or on a massless revolute_revolute rod, a point mass with no joint at all) has an angle no
// constraint sees and no mass resists: phi is a free, massless coordinate. When no force acts on
// it either, any phi(t) satisfies the equations, and the answer a multibody model gives is to
// eliminate it: its angle stays at `angle`, its angular velocity at zero, and it counts as no
// degree of freedom. A torque on it (an applied torque, a rotational spring, a force at a point
// off the origin) would need an infinite angular acceleration; that is refused.
//
//   std::vector<int> held = find_held_rotations(model, 0.0);   // global phi coordinates
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/system_model.h"

namespace periflex {

// Phi coordinates of zero-inertia bodies whose Jacobian column vanishes at every angle (checked
// at q0 and two other angles: each constraint is a first-degree trigonometric polynomial in one
// body's angle, so a derivative zero at two angles apart by less than pi is zero everywhere).
// Throws InputError (at the body) when such a body starts with an angular velocity or a force
// element puts a torque on it at t.
std::vector<int> find_held_rotations(const SystemModel& model, double t);

// Throws NumericalError when a force element puts a torque on a held rotation in g (a load
// that starts later in the run than the set-up check could see).
void check_held_rotations(const SystemModel& model, const std::vector<int>& held, const Eigen::VectorXd& g,
                          double t);

}  // namespace periflex
