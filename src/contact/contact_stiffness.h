// The default penalty stiffness of contact, from the peridynamic material (Silling & Askari's
// short-range force, as LAMMPS's peri pair styles apply it): a pair of particles closer than
// the contact distance repels with 15 c V_i V_j / delta per unit of overlap, c the bond
// micromodulus and delta the horizon; about a quarter of what the bonds hold one particle with
// at a horizon of 3 spacings.
#pragma once

#include "pd/pd_body.h"

namespace periflex {

// 15 c V^2 / delta [N/m] with V the largest particle volume of `flex`.
double default_contact_stiffness(const PdBody& flex);

}  // namespace periflex
