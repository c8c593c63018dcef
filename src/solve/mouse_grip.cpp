#include "solve/mouse_grip.h"

#include <cmath>

namespace periflex {

GripLimits grip_limits(double youngs_modulus, double density, double critical_stretch, double horizon,
                       double thickness, bool hard) {
  const double factor = hard ? kHardGripFactor : 1.0;
  const double wave_speed = std::sqrt(youngs_modulus / density);
  const double stretch = std::isfinite(critical_stretch) && critical_stretch > 0.0 ? critical_stretch : 0.01;
  GripLimits limits;
  limits.max_speed = factor * kGripWaveFraction * wave_speed;
  limits.max_force = factor * youngs_modulus * stretch * 2.0 * kPi * horizon * thickness;
  return limits;
}

Vec2 held_point(const MouseSpringForce& spring, const Eigen::VectorXd& q) {
  if (spring.point.body >= 0) return spring.point.position(q);
  Vec2 sum = Vec2::Zero();
  double weight = 0.0;
  for (size_t k = 0; k < spring.particle_coordinates.size(); ++k) {
    const int c = spring.particle_coordinates[k];
    sum += spring.particle_stiffness[k] * (Vec2(q[c], q[c + 1]) - spring.offsets[k]);
    weight += spring.particle_stiffness[k];
  }
  return weight > 0.0 ? Vec2(sum / weight) : spring.target;
}

double grip_force(const MouseSpringForce& spring, double t, const Eigen::VectorXd& q) {
  return spring.stiffness * (spring.target_at(t) - held_point(spring, q)).norm();
}

void hold_anchor_within_force(MouseSpringForce& spring, double t, double h, const Eigen::VectorXd& q,
                              double max_force) {
  if (max_force <= 0.0 || spring.speed <= 0.0) return;
  const Vec2 held = held_point(spring, q);
  if (spring.stiffness * (spring.target_at(t + h) - held).norm() <= max_force) return;
  // wait: the walk starts again from here at the step's end
  spring.from = spring.target_at(t);
  spring.since = t + h;
}

}  // namespace periflex
