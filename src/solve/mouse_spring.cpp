// The mouse spring: a grab of a rigid body or of a patch of particles, held as stiffly as the
// step allows, its anchor walking to the pointer at a speed the material follows (mouse_grip.h);
// a drag of the same grab moves only the target.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace periflex {

double Simulation::set_mouse_spring(const std::optional<MouseSpring>& spring) {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  const SystemModel& m = *s.model;
  if (!spring) {
    s.dynamics->set_mouse_spring(std::nullopt);
    return 0.0;
  }
  // the same grab again: a drag moves the target only (no new patch, no integrator restart)
  std::optional<MouseSpringForce>& held = s.dynamics->mouse_spring();
  if (held && spring->stiffness <= 0.0 && held->grabbed_body == spring->body &&
      held->grabbed_particle == spring->particle) {
    // (an anchor waiting for the body keeps waiting: its walk resumes where it stands)
    held->from = held->target_at(s.time);
    held->since = std::max(held->since, s.time);
    held->target = spring->target;
    if (held->speed > 0.0) {
      // a hard grip (Shift) taken or let go during the drag
      const double factor = spring->hard == s.grip_hard ? 1.0 : spring->hard ? kHardGripFactor : 1.0 / kHardGripFactor;
      held->speed *= factor;
      s.grip.max_force *= factor;
      s.grip_hard = spring->hard;
    }
    return held->stiffness;
  }

  // How stiff: the held part follows the pointer at an angular frequency omega, so its
  // stiffness is (held mass) omega^2 and its damping 0.7 of critical, 1.4 (held mass) omega.
  // Explicit stepping stays stable with omega dt <= 0.3 and, for particles, with the bonds'
  // highest frequency (2 / critical step) and the spring's together under 2 / dt.
  const double dt = s.live.dt;
  double omega_stable = dt > 0.0 ? 0.3 / dt : 1e300;
  constexpr double kDampingRatio = 0.7;
  MouseSpringForce force;
  force.target = spring->target;
  force.grabbed_body = spring->body;
  force.grabbed_particle = spring->particle;
  if (spring->body >= 0 && spring->body < static_cast<int>(m.bodies.size())) {
    // a rigid body settles on the pointer within about a twentieth of the run (2 Hz over 10 s)
    const double end = s.scene.solver.end_time;
    const double omega = std::min(end > 0.0 ? 2.0 * kPi * 20.0 / end : 2.0 * kPi * 2.0, omega_stable);
    const double mass = m.bodies[spring->body].mass > 0.0 ? m.bodies[spring->body].mass : 1.0;
    force.point = BodyPoint{spring->body, spring->local_point};
    force.stiffness = spring->stiffness > 0.0 ? spring->stiffness : mass * omega * omega;
    force.damping = 2.0 * kDampingRatio * std::sqrt(force.stiffness * mass);
  } else if (spring->particle >= 0) {
    // snapshot order: the flexible bodies' particles concatenated
    int first = 0;
    for (const auto& flex : m.flex_bodies) {
      if (spring->particle >= first + flex->particle_count()) {
        first += flex->particle_count();
        continue;
      }
      // The patch within one horizon of the grabbed particle (as it lies now): one particle
      // alone is held back by its bonds and barely moves; a patch as wide as the bonds' reach
      // pulls the body as a finger would. It is held as stiffly as the step allows, since a
      // softer grip could not compete with the bonds around it and the body would not deform.
      const int offset = flex->coordinate_offset();
      const Eigen::VectorXd& q = s.state.q;
      const Vec2 grabbed(q[offset + 2 * (spring->particle - first)], q[offset + 2 * (spring->particle - first) + 1]);
      const double reach = flex->horizon();
      // the patch starts where it is and its anchor walks to the pointer at a speed the material
      // follows, pulling at most with the force the patch carries (mouse_grip.h): a pull, not
      // an impact, however fast the hand moved in the window's slow motion
      const auto def = std::find_if(s.scene.flex_bodies.begin(), s.scene.flex_bodies.end(),
                                    [&](const FlexBodyDef& d) { return d.name == flex->name(); });
      const double density = flex->volumes()[spring->particle - first] > 0.0
                                 ? flex->masses()[spring->particle - first] / flex->volumes()[spring->particle - first]
                                 : 0.0;
      if (def != s.scene.flex_bodies.end() && density > 0.0) {
        s.grip = grip_limits(def->material.youngs_modulus, density, flex->critical_stretch(), reach, def->thickness,
                             spring->hard);
      } else {
        s.grip = GripLimits{dt > 0.0 ? reach / (200.0 * dt) : 0.0, 0.0};
      }
      s.grip_hard = spring->hard;
      force.from = grabbed;
      force.since = s.time;
      force.speed = s.grip.max_speed;
      double omega = omega_stable;
      if (s.critical_step > 0.0 && dt > 0.0) {
        const double ratio = std::min(1.0, dt / s.critical_step);
        omega = std::min(omega, std::sqrt(1.0 - ratio * ratio) / dt);
      }
      const std::vector<double>& masses = flex->masses();
      for (int i = 0; i < flex->particle_count(); ++i) {
        const Vec2 p(q[offset + 2 * i], q[offset + 2 * i + 1]);
        if ((p - grabbed).squaredNorm() > reach * reach) continue;
        const double k = masses[i] * omega * omega;
        force.particle_coordinates.push_back(offset + 2 * i);
        force.offsets.push_back(p - grabbed);
        force.particle_stiffness.push_back(k);
        force.particle_damping.push_back(2.0 * kDampingRatio * masses[i] * omega);
        force.stiffness += k;
        force.damping += force.particle_damping.back();
      }
      if (spring->stiffness > 0.0 && force.stiffness > 0.0) {
        // a given total stiffness, shared in proportion to the masses
        const double scale = spring->stiffness / force.stiffness;
        for (double& k : force.particle_stiffness) k *= scale;
        for (double& c : force.particle_damping) c *= std::sqrt(scale);
        force.stiffness = spring->stiffness;
      }
      break;
    }
    if (force.particle_coordinates.empty()) return 0.0;
  } else {
    return 0.0;
  }
  s.dynamics->set_mouse_spring(force);
  s.integrator->reset();
  return force.stiffness;
}

}  // namespace periflex
