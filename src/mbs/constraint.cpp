#include "mbs/constraint.h"

namespace periflex {

void Constraint::time_derivative(const Eigen::VectorXd& q, double t, double* phi_t) const {
  for (int k = 0; k < rows(); ++k) phi_t[k] = 0.0;
}

}  // namespace periflex
