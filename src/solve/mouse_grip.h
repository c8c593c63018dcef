// The mouse's grip on a flexible body, as a pull rather than an impact: the spring's anchor walks
// to the pointer at a speed the material can follow (a small fraction of its wave speed, in
// simulated time, however fast the hand moved), and it waits while its pull is above a limit
// near what the held patch can carry. Simulation::set_mouse_spring sets them; the window shows them.
#pragma once

#include <Eigen/Core>

#include "core/vec2.h"
#include "solve/dynamics.h"

namespace periflex {

// The anchor's speed as a fraction of the bar wave speed sqrt(E / rho): a patch moved at v sends
// out a strain of about v / c, here 1e-3 (a tenth to a fiftieth of the critical stretch of the
// shipped materials); a hard grip (Shift) moves ten times faster and pulls ten times harder.
constexpr double kGripWaveFraction = 1e-3;
constexpr double kHardGripFactor = 10.0;

struct GripLimits {
  double max_speed = 0.0;  // [m/s] of the anchor in simulated time
  double max_force = 0.0;  // [N] of the spring's pull
};

// Limits of a grab of a patch one horizon wide on a body of Young's modulus E [Pa], density rho
// [kg/m^3], critical stretch s0 (infinite without fracture: taken as 0.01), horizon delta [m] and
// thickness t [m]. The force limit E s0 (2 pi delta) t is the pull at which the material around
// the patch's whole rim reaches its breaking stretch: enough to open a notch and run a crack
// from it (a third of it could not on the notched plate), while the patch tears out before the
// body can be flung.
GripLimits grip_limits(double youngs_modulus, double density, double critical_stretch, double horizon,
                       double thickness, bool hard);

// Where the patch is held now: the stiffness-weighted mean of its particles less their offsets
// (the point the anchor pulls towards its own place). A rigid grab: its point.
Vec2 held_point(const MouseSpringForce& spring, const Eigen::VectorXd& q);

// The spring's pull [N] at (t, q): total stiffness times the anchor's lead on the held point.
double grip_force(const MouseSpringForce& spring, double t, const Eigen::VectorXd& q);

// Before a step from t to t + h: when the anchor's lead at t + h would pull harder than
// max_force, the anchor stays where it is at t for the step (it walks on once the body has
// followed). max_force <= 0: no limit.
void hold_anchor_within_force(MouseSpringForce& spring, double t, double h, const Eigen::VectorXd& q,
                              double max_force);

}  // namespace periflex
