// Adaptive Dormand-Prince 5(4) (Dormand & Prince 1980; Hairer, Norsett & Wanner, "Solving
// ODEs I", II.5): a fifth-order step with an embedded fourth-order error estimate, first
// stage same as last (FSAL), and the usual step-size controller. One call to step() covers
// the macro step dt with as many internal steps as the tolerances need.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"
#include "solve/integrator.h"

namespace periflex {

namespace {

constexpr int kStages = 7;
constexpr std::array<double, kStages> kC = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
constexpr double kA[kStages][kStages] = {
    {0, 0, 0, 0, 0, 0, 0},
    {1.0 / 5, 0, 0, 0, 0, 0, 0},
    {3.0 / 40, 9.0 / 40, 0, 0, 0, 0, 0},
    {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0, 0},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0, 0},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0, 0},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}};
// fifth-order weights (the last row of A) minus the fourth-order ones
constexpr std::array<double, kStages> kE = {71.0 / 57600,      0.0,          -71.0 / 16695, 71.0 / 1920,
                                            -17253.0 / 339200, 22.0 / 525,   -1.0 / 40};

class DormandPrince final : public Integrator {
 public:
  DormandPrince(double rtol, double atol) : Integrator(IntegratorKind::kDopri54), rtol_(rtol), atol_(atol) {}
  void reset() override { fsal_valid_ = false; }

  void step(OdeSystem& system, double t, double dt, OdeState& s) override {
    const double t_end = t + dt;
    double h = h_ > 0.0 ? std::min(h_, dt) : dt;
    while (t < t_end) {
      // never overshoot the end of the macro step, and do not leave a sliver behind
      const double remaining = t_end - t;
      if (h >= remaining || remaining - h < 1e-3 * h) h = remaining;
      const double error = attempt(system, t, h, s);
      if (error <= 1.0) {
        t = (h == remaining) ? t_end : t + h;
        s.q = q_new_;
        s.qd = qd_new_;
        s.work = work_new_;
        // the last stage was evaluated at the new state: it starts the next step
        kqd_[0] = kqd_[6];
        kqdd_[0] = kqdd_[6];
        kw_[0] = kw_[6];
        fsal_valid_ = true;
        fsal_time_ = t;
        ++accepted_;
      } else {
        ++rejected_;
      }
      // step-size controller: safety 0.9, growth limited to [0.2, 5]
      const double factor = error == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(error, -0.2), 0.2, 5.0);
      const double next = h * (error <= 1.0 ? factor : std::min(factor, 1.0));
      if (!(next > 1e-14 * std::max(1.0, std::abs(t)))) {
        throw NumericalError({"adaptive step size", -1, t, "the step size fell below round-off (stiff or singular "
                              "dynamics)", "loosen solver.rtol / solver.atol, or use a smaller solver.dt"});
      }
      h = next;
    }
    h_ = h;
  }

 protected:
  // the step size carried over, and the last stage (first same as last) with its time
  void save_steps(IntegratorCache& out) const override {
    out.scalars = {h_, fsal_valid_ ? 1.0 : 0.0, fsal_time_, kw_[0][0], kw_[0][1], kw_[0][2]};
    out.vectors = {kqd_[0], kqdd_[0]};
  }
  void restore_steps(const IntegratorCache& in) override {
    if (in.scalars.size() != 6 || in.vectors.size() != 2) return;
    h_ = in.scalars[0];
    fsal_valid_ = in.scalars[1] != 0.0;
    fsal_time_ = in.scalars[2];
    kw_[0] = Eigen::Vector3d(in.scalars[3], in.scalars[4], in.scalars[5]);
    kqd_[0] = in.vectors[0];
    kqdd_[0] = in.vectors[1];
  }

 private:
  // One trial step of size h from (t, s); fills q_new_, qd_new_, work_new_; returns the scaled error.
  double attempt(OdeSystem& system, double t, double h, const OdeState& s) {
    const Eigen::Index n = s.q.size();
    for (int k = 0; k < kStages; ++k) {
      kqd_[k].resize(n);
      kqdd_[k].resize(n);
    }
    if (!fsal_valid_ || fsal_time_ != t) {
      kqd_[0] = s.qd;
      system.derivative(t, s.q, s.qd, kqdd_[0], kw_[0]);
      // a rejected attempt retries from the same first stage
      fsal_valid_ = true;
      fsal_time_ = t;
    }
    // stages 2..7: stage state from the earlier slopes
    for (int k = 1; k < kStages; ++k) {
      q_stage_ = s.q;
      qd_stage_ = s.qd;
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      for (int j = 0; j < k; ++j) {
        if (kA[k][j] == 0.0) continue;
        q_stage_ += h * kA[k][j] * kqd_[j];
        qd_stage_ += h * kA[k][j] * kqdd_[j];
        w += h * kA[k][j] * kw_[j];
      }
      if (k == kStages - 1) {
        q_new_ = q_stage_;
        qd_new_ = qd_stage_;
        work_new_ = s.work + w;
      }
      kqd_[k] = qd_stage_;
      system.derivative(t + kC[k] * h, q_stage_, qd_stage_, kqdd_[k], kw_[k]);
    }
    // embedded error estimate, RMS over q and qd scaled by atol + rtol |y|
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      double eq = 0.0, eqd = 0.0;
      for (int k = 0; k < kStages; ++k) {
        eq += kE[k] * kqd_[k][i];
        eqd += kE[k] * kqdd_[k][i];
      }
      const double sq = atol_ + rtol_ * std::max(std::abs(s.q[i]), std::abs(q_new_[i]));
      const double sqd = atol_ + rtol_ * std::max(std::abs(s.qd[i]), std::abs(qd_new_[i]));
      sum += (h * eq / sq) * (h * eq / sq) + (h * eqd / sqd) * (h * eqd / sqd);
    }
    const double error = n > 0 ? std::sqrt(sum / (2.0 * n)) : 0.0;
    return std::isfinite(error) ? error : 1e10;
  }

  double rtol_, atol_;
  double h_ = 0.0;  // internal step carried from one macro step to the next
  std::array<Eigen::VectorXd, kStages> kqd_, kqdd_;
  std::array<Eigen::Vector3d, kStages> kw_;
  Eigen::VectorXd q_stage_, qd_stage_, q_new_, qd_new_;
  Eigen::Vector3d work_new_ = Eigen::Vector3d::Zero();
  bool fsal_valid_ = false;
  double fsal_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Integrator> make_dormand_prince(const SolverDef& solver) {
  if (!(solver.rtol > 0.0) || !(solver.atol > 0.0)) {
    throw InputError({"", 0, 0, "solver.rtol"}, "dopri54 needs solver.rtol > 0 and solver.atol > 0");
  }
  return std::make_unique<DormandPrince>(solver.rtol, solver.atol);
}

}  // namespace periflex
