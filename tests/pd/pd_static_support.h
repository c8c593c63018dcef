// Static equilibrium of one peridynamic body for the tests: K u = f by conjugate gradients, K v
// taken as the central difference of the body's forces (exact for its quadratic energy at small
// strain), and a strip pulled at its ends. Shared by the state-based tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "pd/pd_body.h"

namespace periflex::test {

// q of the body's particles at rest (the body's slice starts at 0).
inline Eigen::VectorXd reference_q(const PdBody& body) {
  return Eigen::Map<const Eigen::VectorXd>(body.reference_positions().data(), body.reference_positions().size());
}

// Forces at q (the body's slice starts at 0).
inline Eigen::VectorXd forces_at(PdBody& body, const Eigen::VectorXd& q) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body.add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  return g;
}

// K u = f on the coordinates not flagged in `fixed` (held at 0), by conjugate gradients to a
// residual of 1e-10 of |f|.
inline Eigen::VectorXd static_solution(PdBody& body, const Eigen::VectorXd& f, const Eigen::VectorXd& fixed) {
  const Eigen::VectorXd q0 = reference_q(body);
  const Eigen::VectorXd free = Eigen::VectorXd::Ones(q0.size()) - fixed;
  const double h = 1e-9;
  auto apply = [&](const Eigen::VectorXd& v) {
    const double scale = h / std::max(v.cwiseAbs().maxCoeff(), 1e-300);
    const Eigen::VectorXd kv = -(forces_at(body, q0 + scale * v) - forces_at(body, q0 - scale * v)) / (2 * scale);
    return Eigen::VectorXd(kv.cwiseProduct(free));
  };
  Eigen::VectorXd u = Eigen::VectorXd::Zero(q0.size()), r = f.cwiseProduct(free), p = r;
  double rr = r.squaredNorm();
  const double stop = 1e-20 * rr;
  for (int it = 0; it < 10 * q0.size() && rr > stop; ++it) {
    const Eigen::VectorXd kp = apply(p);
    const double alpha = rr / p.dot(kp);
    u += alpha * p;
    r -= alpha * kp;
    const double next = r.squaredNorm();
    p = r + (next / rr) * p;
    rr = next;
  }
  return u;
}

// A strip pulled at its right end by a uniform axial force per particle of the last column, its
// left column held in x (and its middle particle in y).
inline Eigen::VectorXd static_tension(PdBody& body, double force_per_particle) {
  const std::vector<double>& x = body.reference_positions();
  const int n = body.particle_count();
  double x_min = 1e300, x_max = -1e300;
  for (int i = 0; i < n; ++i) {
    x_min = std::min(x_min, x[2 * i]);
    x_max = std::max(x_max, x[2 * i]);
  }
  const double dx = body.grid_spacing();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * n), fixed = Eigen::VectorXd::Zero(2 * n);
  int anchor = -1;
  for (int i = 0; i < n; ++i) {
    if (x[2 * i] > x_max - 0.5 * dx) f[2 * i] = force_per_particle;
    if (x[2 * i] < x_min + 0.5 * dx) {
      fixed[2 * i] = 1.0;
      if (anchor < 0 || std::abs(x[2 * i + 1]) < std::abs(x[2 * anchor + 1])) anchor = i;
    }
  }
  fixed[2 * anchor + 1] = 1.0;
  return static_solution(body, f, fixed);
}

// The hoop strain at the top of a hole of radius a centred at the origin, from the displacements u
// of its rim particles: (A0, A2, B2) of u_r = A0 + A2 cos 2 phi and u_theta = B2 sin 2 phi fitted by
// least squares (reference polar angle phi), the form the Kirsch displacements take on the hole's
// edge, and then (u_r + du_theta / dphi) / a = (A0 - A2 - 2 B2) / a at phi = 90 degrees.
inline double rim_hoop_strain(const std::vector<double>& x, const std::vector<int>& rim, const Eigen::VectorXd& u,
                       double a) {
  Eigen::MatrixXd fit(rim.size(), 2);
  Eigen::VectorXd ur(rim.size()), ut(rim.size()), s2(rim.size());
  for (size_t k = 0; k < rim.size(); ++k) {
    const int i = rim[k];
    const double r = std::hypot(x[2 * i], x[2 * i + 1]), phi = std::atan2(x[2 * i + 1], x[2 * i]);
    const double c = x[2 * i] / r, s = x[2 * i + 1] / r;
    fit.row(k) << 1.0, std::cos(2 * phi);
    s2[k] = std::sin(2 * phi);
    ur[k] = c * u[2 * i] + s * u[2 * i + 1];
    ut[k] = -s * u[2 * i] + c * u[2 * i + 1];
  }
  const Eigen::Vector2d radial = fit.colPivHouseholderQr().solve(ur);
  const double b2 = s2.dot(ut) / s2.squaredNorm();
  return (radial[0] - radial[1] - 2 * b2) / a;
}

}  // namespace periflex::test
