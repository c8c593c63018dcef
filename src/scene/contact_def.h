// What a [[contact]] table declares (docs/scenes.md, docs/contact.md). Kept apart from
// scene_def.h so the contact definitions read as one unit.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"

namespace periflex {

struct ContactDef {
  enum class Kind {
    kRigidParticles,  // the drawing shapes of a rigid body against the particles of a flexible body
    kParticles,       // particles of the listed flexible bodies against each other (bonded pairs excepted)
    kRigid            // the drawing shapes of two rigid bodies against each other
  };
  Kind kind = Kind::kRigidParticles;
  std::string name;
  std::string body;                      // rigid_particles: the rigid body; rigid: the first (body_i)
  std::string body_j;                    // rigid: the second rigid body
  std::vector<std::string> flex_bodies;  // rigid_particles: one; particles: one or more
  double stiffness = 0.0;        // penalty stiffness [N/m] per particle (pair, contact point); 0: from the micromodulus
  double restitution = 1.0;      // coefficient of restitution of one contact, in (0, 1]
  double friction = 0.0;         // Coulomb coefficient mu (rigid_particles, rigid)
  double friction_velocity = 1e-3;  // sliding speed [m/s] below which friction is scaled down (regularised)
  double margin = -1.0;          // rigid_particles: contact when a particle is nearer the shape than this; < 0: dx / 2
  double distance_ratio = 0.9;   // particles: contact below this fraction of the grid spacing
  double skin_ratio = 0.5;       // particles: Verlet skin as a fraction of the grid spacing
  SourceLocation where;
  SourceLocation stiffness_where;   // where stiffness was given (line 0: not given)
};

}  // namespace periflex
