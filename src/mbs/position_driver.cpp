#include "mbs/position_driver.h"

#include "mbs/revolute_joint.h"

namespace periflex {

PositionDriver::PositionDriver(std::string name, AxisGap gap, TimeFunction f)
    : name_(std::move(name)), gap_(gap), f_(std::move(f)) {
  gap_.axis.normalize();
}

void PositionDriver::residual(const Eigen::VectorXd& q, double t, double* phi) const {
  phi[0] = gap_.value(q) - f_(t);
}

void PositionDriver::jacobian(const Eigen::VectorXd& q, double, int row0, Triplets& out) const {
  gap_.gradient(q, row0, out);
}

void PositionDriver::time_derivative(const Eigen::VectorXd&, double t, double* phi_t) const { phi_t[0] = -f_.d1(t); }

void PositionDriver::gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, double* out) const {
  out[0] = gap_.gamma(q, qd) + f_.d2(t);
}

void PositionDriver::coordinates(std::vector<int>& out) const {
  append_body_coordinates(gap_.a.body, out);
  append_body_coordinates(gap_.b.body, out);
}

}  // namespace periflex
