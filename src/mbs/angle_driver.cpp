#include "mbs/angle_driver.h"

#include "mbs/body_point.h"

namespace periflex {

AngleDriver::AngleDriver(std::string name, int plus_body, int minus_body, TimeFunction f)
    : name_(std::move(name)), plus_(plus_body), minus_(minus_body), f_(std::move(f)) {}

static double body_angle(const Eigen::VectorXd& q, int body) { return body < 0 ? 0.0 : q[3 * body + 2]; }

void AngleDriver::residual(const Eigen::VectorXd& q, double t, double* phi) const {
  phi[0] = body_angle(q, plus_) - body_angle(q, minus_) - f_(t);
}

void AngleDriver::jacobian(const Eigen::VectorXd&, double, int row0, Triplets& out) const {
  if (plus_ >= 0) put_entry(out, row0, 3 * plus_ + 2, 1.0);
  if (minus_ >= 0) put_entry(out, row0, 3 * minus_ + 2, -1.0);
}

void AngleDriver::time_derivative(const Eigen::VectorXd&, double t, double* phi_t) const { phi_t[0] = -f_.d1(t); }

// Phi_tt = -f'' and nothing else depends on velocity: gamma = f''.
void AngleDriver::gamma(const Eigen::VectorXd&, const Eigen::VectorXd&, double t, double* out) const {
  out[0] = f_.d2(t);
}

void AngleDriver::coordinates(std::vector<int>& out) const {
  if (plus_ >= 0) out.push_back(3 * plus_ + 2);
  if (minus_ >= 0) out.push_back(3 * minus_ + 2);
}

}  // namespace periflex
