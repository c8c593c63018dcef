// Helpers shared by the peridynamics tests: plate definitions, affine deformations, and a
// small explicit velocity-Verlet loop over one PdBody (independent of the solver layer).
#pragma once

#include <omp.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "pd/pd_body.h"
#include "scene/scene_def.h"

namespace periflex::test {

// Runs the enclosing scope on one OpenMP thread. The dynamic tests check physics, not parallel
// speed (PdDeterminism covers the threaded path); on a machine shared with other jobs a thread
// that is descheduled at every barrier makes a threaded run many times slower than a serial one.
class SerialScope {
 public:
  SerialScope() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~SerialScope() { omp_set_num_threads(saved_); }
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;

 private:
  int saved_;
};

// A rectangle centred at the origin.
inline ShapeDef box(double width, double height, Vec2 center = Vec2::Zero()) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kBox;
  s.center = center;
  s.width = width;
  s.height = height;
  return s;
}

// A plane-stress body of the given box with E = 72 GPa, rho = 2440 kg/m^3 (soda-lime glass).
inline FlexBodyDef glass_plate(double width, double height, double dx, double thickness = 1e-3) {
  FlexBodyDef def;
  def.name = "plate";
  def.shape = box(width, height);
  def.grid_spacing = dx;
  def.thickness = thickness;
  def.horizon_ratio = 3.0;
  def.material.youngs_modulus = 72e9;
  def.material.density = 2440.0;
  def.material.fracture_energy = 3.8;
  return def;
}

// Mean velocity component `comp` (0: x, 1: y) of the particles in the grid column nearest reference x = at.
inline double column_velocity(const PdBody& body, const Eigen::VectorXd& qd, double at, int comp = 0) {
  const std::vector<double>& x = body.reference_positions();
  const double column = x[2 * body.nearest_particle(Vec2(at, 0.0))];
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < body.particle_count(); ++i) {
    if (std::abs(x[2 * i] - column) < 0.25 * body.grid_spacing()) {
      sum += qd[2 * i + comp];
      ++count;
    }
  }
  return sum / count;
}

// Uniaxial stress along x in plane stress with nu = 1/3: eps_yy = -eps / 3, W = E eps^2 / 2.
inline Eigen::Matrix2d uniaxial(double eps) {
  Eigen::Matrix2d h;
  h << eps, 0.0, 0.0, -eps / 3.0;
  return h;
}

// Index of the particle nearest the centre of a body (an interior particle).
inline int centre_particle(const PdBody& body) { return body.nearest_particle(Vec2(1e-9, 1e-9)); }

// q of the body's particles (offset 0) displaced by the affine map X -> X + H X.
inline Eigen::VectorXd affine_positions(const PdBody& body, const Eigen::Matrix2d& h) {
  const std::vector<double>& x = body.reference_positions();
  Eigen::VectorXd q(x.size());
  for (size_t i = 0; i < x.size() / 2; ++i) {
    const Vec2 p(x[2 * i], x[2 * i + 1]);
    const Vec2 y = p + h * p;
    q[2 * i] = y.x();
    q[2 * i + 1] = y.y();
  }
  return q;
}

// Explicit velocity Verlet on one body whose coordinates start at q[0]. Prescribed coordinates
// follow their functions; the others integrate M qdd = g. `observe(t, q, qd)` runs after every step.
class VerletLoop {
 public:
  explicit VerletLoop(PdBody& body) : body_(body) {
    q_ = Eigen::Map<const Eigen::VectorXd>(body.reference_positions().data(), body.reference_positions().size());
    const std::vector<double> v0 = body.initial_velocities();
    qd_ = Eigen::Map<const Eigen::VectorXd>(v0.data(), v0.size());
    inv_mass_.resize(q_.size());
    for (int i = 0; i < body.particle_count(); ++i) inv_mass_[2 * i] = inv_mass_[2 * i + 1] = 1.0 / body.masses()[i];
    prescribed_ = body.prescribed_coordinates();
    for (const PrescribedCoordinate& pc : prescribed_) inv_mass_[pc.coordinate] = 0.0;
    impose(0.0);
    accel_ = acceleration(0.0);
  }

  Eigen::VectorXd& q() { return q_; }
  Eigen::VectorXd& qd() { return qd_; }
  double time() const { return t_; }

  // One step of length dt; with `fracture` the bonds broken in it are reported (by default they
  // break in the force evaluation at the end of the step; a body set to break them after the step
  // breaks them here, and the acceleration is evaluated again without them, as the solver does).
  FractureUpdate step(double dt, bool fracture = false) {
    body_.set_step_end(t_ + dt, 0.5 * dt);
    qd_ += 0.5 * dt * accel_;
    q_ += dt * qd_;
    t_ += dt;
    impose(t_);
    accel_ = acceleration(t_);
    qd_ += 0.5 * dt * accel_;
    impose(t_);
    if (!fracture) return FractureUpdate{};
    const FractureUpdate update = body_.update_fracture(q_);
    if (update.forces_stale) accel_ = acceleration(t_);
    return update;
  }

  double kinetic_energy() const {
    double e = 0.0;
    for (int i = 0; i < body_.particle_count(); ++i)
      e += 0.5 * body_.masses()[i] * (qd_[2 * i] * qd_[2 * i] + qd_[2 * i + 1] * qd_[2 * i + 1]);
    return e;
  }

 private:
  void impose(double t) {
    for (const PrescribedCoordinate& pc : prescribed_) {
      q_[pc.coordinate] = pc.reference + pc.displacement(t);
      qd_[pc.coordinate] = pc.displacement.d1(t);
    }
  }
  Eigen::VectorXd acceleration(double t) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q_.size());
    body_.add_forces(q_, qd_, t, g);
    return g.cwiseProduct(inv_mass_);
  }

  PdBody& body_;
  Eigen::VectorXd q_, qd_, accel_, inv_mass_;
  std::vector<PrescribedCoordinate> prescribed_;
  double t_ = 0.0;
};

// A plate torn apart by opposite x-velocities (+-1 m/s) of its halves: 80 velocity Verlet steps of
// 0.4 times the critical step with fracture on, on `threads` threads (the setting restored after).
struct TornPlate {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q;
};

inline TornPlate tear_plate(const FlexBodyDef& def, int threads) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  TornPlate torn{PdBody::build(def, 0), {}};
  VerletLoop loop(*torn.body);
  const std::vector<double>& x = torn.body->reference_positions();
  for (int i = 0; i < torn.body->particle_count(); ++i) loop.qd()[2 * i] = x[2 * i] > 0.0 ? 1.0 : -1.0;
  const double dt = 0.4 * torn.body->critical_time_step();
  for (int k = 0; k < 80; ++k) loop.step(dt, true);
  torn.q = loop.q();
  omp_set_num_threads(saved);
  return torn;
}

}  // namespace periflex::test
