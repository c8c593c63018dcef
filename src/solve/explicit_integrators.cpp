// The fixed-step explicit integrators: semi-implicit (symplectic) Euler, velocity Verlet and
// classical Runge-Kutta 4 (built by make_integrator in integrator.cpp).
#include <array>

#include "core/parallel_chunks.h"
#include "solve/integrator.h"

namespace periflex {

namespace {

// qd += half_dt qdd, then q += dt qd, entry by entry in one pass over memory (in chunks on the
// OpenMP threads for large models; each entry on its own, so the same bits on any thread count).
void kick_and_drift(Eigen::VectorXd& q, Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, double half_dt, double dt) {
  double* pq = q.data();
  double* pv = qd.data();
  const double* pa = qdd.data();
  parallel_chunks(q.size(), [&](int64_t, int64_t begin, int64_t end) {
#pragma omp simd
    for (int64_t i = begin; i < end; ++i) {
      pv[i] += half_dt * pa[i];
      pq[i] += dt * pv[i];
    }
  });
}

// qd += half_dt qdd
void kick(Eigen::VectorXd& qd, const Eigen::VectorXd& qdd, double half_dt) {
  double* pv = qd.data();
  const double* pa = qdd.data();
  parallel_chunks(qd.size(), [&](int64_t, int64_t begin, int64_t end) {
#pragma omp simd
    for (int64_t i = begin; i < end; ++i) pv[i] += half_dt * pa[i];
  });
}

// Semi-implicit Euler: qd += h qdd(q, qd); q += h qd_new. First order, symplectic for
// separable Hamiltonians, one force evaluation per step.
class SymplecticEuler final : public Integrator {
 public:
  SymplecticEuler() : Integrator(IntegratorKind::kSymplecticEuler) {}
  void step(OdeSystem& system, double t, double dt, OdeState& s) override {
    system.derivative(t, s.q, s.qd, qdd_, power_);
    s.qd += dt * qdd_;
    s.q += dt * s.qd;
    s.work += dt * power_;
    ++accepted_;
  }

 private:
  Eigen::VectorXd qdd_;
  Eigen::Vector3d power_;
};

// Velocity Verlet: half kick, drift, force at the new positions, half kick. Second order,
// symplectic; the end acceleration is kept for the next step unless the state is edited.
class VelocityVerlet final : public Integrator {
 public:
  VelocityVerlet() : Integrator(IntegratorKind::kVerlet) {}
  void step(OdeSystem& system, double t, double dt, OdeState& s) override {
    if (!cached_ || cached_time_ != t) system.derivative(t, s.q, s.qd, qdd_, power_);
    const Eigen::Vector3d power_start = power_;
    kick_and_drift(s.q, s.qd, qdd_, 0.5 * dt, dt);
    // velocity-dependent forces see the half-step velocity
    system.derivative(t + dt, s.q, s.qd, qdd_, power_);
    kick(s.qd, qdd_, 0.5 * dt);
    s.work += 0.5 * dt * (power_start + power_);
    cached_ = true;
    cached_time_ = t + dt;
    ++accepted_;
  }
  void reset() override { cached_ = false; }

 protected:
  // the end acceleration and power of the last step, and when they were evaluated
  void save_steps(IntegratorCache& out) const override {
    out.scalars = {cached_ ? 1.0 : 0.0, cached_time_, power_[0], power_[1], power_[2]};
    out.vectors = {qdd_};
  }
  void restore_steps(const IntegratorCache& in) override {
    if (in.scalars.size() != 5 || in.vectors.size() != 1) return;
    cached_ = in.scalars[0] != 0.0;
    cached_time_ = in.scalars[1];
    power_ = Eigen::Vector3d(in.scalars[2], in.scalars[3], in.scalars[4]);
    qdd_ = in.vectors[0];
  }

 private:
  Eigen::VectorXd qdd_;
  Eigen::Vector3d power_;
  bool cached_ = false;
  double cached_time_ = 0.0;
};

// Classical fourth-order Runge-Kutta on (q, qd, work): four evaluations per step.
class RungeKutta4 final : public Integrator {
 public:
  RungeKutta4() : Integrator(IntegratorKind::kRk4) {}
  void step(OdeSystem& system, double t, double dt, OdeState& s) override {
    static constexpr std::array<double, 4> kC = {0.0, 0.5, 0.5, 1.0};
    static constexpr std::array<double, 4> kB = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    // the start state and the weighted sums of the slopes, in kept buffers (no allocation)
    q0_ = s.q;
    qd0_ = s.qd;
    dq_.setZero(q0_.size());
    dqd_.setZero(q0_.size());
    const Eigen::VectorXd &q0 = q0_, &qd0 = qd0_;
    Eigen::VectorXd &dq = dq_, &dqd = dqd_;
    Eigen::Vector3d dwork = Eigen::Vector3d::Zero();
    // stage k evaluates at q0 + c_k h K_{k-1}; the stage velocity is the position slope
    for (int k = 0; k < 4; ++k) {
      if (k == 0) {
        q_stage_ = q0;
        qd_stage_ = qd0;
      } else {
        q_stage_ = q0 + kC[k] * dt * qd_stage_;
        qd_stage_ = qd0 + kC[k] * dt * qdd_;
      }
      system.derivative(t + kC[k] * dt, q_stage_, qd_stage_, qdd_, power_);
      dq += kB[k] * qd_stage_;
      dqd += kB[k] * qdd_;
      dwork += kB[k] * power_;
    }
    s.q = q0 + dt * dq;
    s.qd = qd0 + dt * dqd;
    s.work += dt * dwork;
    ++accepted_;
  }

 private:
  Eigen::VectorXd q0_, qd0_, dq_, dqd_, q_stage_, qd_stage_, qdd_;
  Eigen::Vector3d power_;
};

}  // namespace

std::unique_ptr<Integrator> make_symplectic_euler() { return std::make_unique<SymplecticEuler>(); }
std::unique_ptr<Integrator> make_velocity_verlet() { return std::make_unique<VelocityVerlet>(); }
std::unique_ptr<Integrator> make_runge_kutta4() { return std::make_unique<RungeKutta4>(); }

}  // namespace periflex
