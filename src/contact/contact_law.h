// The force law of one contact, shared by every contact model (docs/contact.md): a penalty
// spring on the penetration depth d with a dashpot on its rate, which may lower the push to zero
// but never pull, and regularised Coulomb friction against the sliding velocity:
//   F_n = max(0, k d + c d_dot)                 along the normal n
//   F_t = -mu F_n v_t / max(|v_t|, v_reg)       v_t the tangential part of the relative velocity
// The power the dashpot and friction take out, (F_n - k d) d_dot - F_t . v_t >= 0, comes back
// with the force so that the energy balance can book it. Inline: it runs once per contact pair
// in the particle loops.
#pragma once

#include <algorithm>

#include "core/vec2.h"

namespace periflex {

// What one contact gives: the force on the side pushed along n, the normal force magnitude and
// the power dissipated.
struct ContactForce {
  Vec2 force = Vec2::Zero();
  double normal = 0.0;
  double dissipation = 0.0;
};

// The force at penetration `depth` > 0 along the unit `normal` (out of the other side, towards
// the side pushed), with stiffness k [N/m], dashpot c [N s/m], friction coefficient mu and
// regularising speed v_reg. `v_rel` is the velocity of the side pushed relative to the other at
// the contact, or null for a state without velocities (then neither dashpot nor friction act).
inline ContactForce contact_force(double k, double c, double depth, const Vec2& normal, const Vec2* v_rel,
                                  double mu = 0.0, double v_reg = 0.0) {
  ContactForce out;
  const double depth_rate = v_rel ? -normal.dot(*v_rel) : 0.0;
  out.normal = std::max(0.0, k * depth + c * depth_rate);
  out.dissipation = (out.normal - k * depth) * depth_rate;
  out.force = out.normal * normal;
  if (mu > 0.0 && v_rel) {
    const Vec2 v_t = *v_rel - normal.dot(*v_rel) * normal;
    const Vec2 f_t = -mu * out.normal / std::max(v_t.norm(), v_reg) * v_t;
    out.dissipation -= f_t.dot(v_t);
    out.force += f_t;
  }
  return out;
}

}  // namespace periflex
