#include "solve/integrator_hht.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "solve/iteration_matrix_factors.h"

namespace periflex {

namespace {

constexpr int kMaxIterations = 25;
constexpr double kNewtonTolerance = 1e-10;  // position increment / size of the configuration

class Hht final : public Integrator {
 public:
  explicit Hht(double alpha)
      : Integrator(IntegratorKind::kHht), alpha_(alpha), gamma_(0.5 - alpha), beta_(0.25 * (1.0 - alpha) * (1.0 - alpha)) {}

  // The stepper resets after a projection or broken bonds, which move the state by no more than
  // the step's own error: the algorithmic acceleration is then kept (dropping it would cost the
  // second order), and only a real edit of the state (checked at the next step) restarts.
  void reset() override { edited_ = true; }

  void step(OdeSystem& system, double t, double h, OdeState& s) override {
    const Eigen::Index n = s.q.size();
    // the acceleration at the start: kept from the last step, or evaluated afresh
    // (the caller's clock may round differently from t + h: a millionth of a step is the same time)
    const bool same_time = std::abs(cached_time_ - t) <= 1e-6 * h;
    if (!cached_ || !same_time || a0_.size() != n || (edited_ && moved_far(s))) {
      system.derivative(t, s.q, s.qd, f0_, power0_);
      a0_ = f0_;
      cached_ = true;
    } else if (edited_ && (s.q != q_end_ || s.qd != v_end_)) {
      // a small correction: the force term of the start follows the corrected state
      system.derivative(t, s.q, s.qd, f0_, power0_);
    }
    edited_ = false;
    current_ = matrix_for(h);

    bool retried = false;
    for (;;) {
      if (solve_step(system, t, h, s)) break;
      // one retry from scratch: a fresh sparsity pattern and tangent
      if (retried) fail(t, h);
      retried = true;
      pattern_valid_ = false;
      matrices_[current_].valid = false;
    }
    s.work += 0.5 * h * (power0_ + power1_);
    s.q = q1_;
    s.qd = v1_;
    a0_ = a1_;
    f0_ = f1_;
    power0_ = power1_;
    q_end_ = s.q;
    v_end_ = s.qd;
    cached_time_ = t + h;
    ++accepted_;
  }

 protected:
  // The start of the next step: the algorithmic acceleration and force term the last step
  // ended with. The iteration matrix is not kept: a restored HHT builds a fresh tangent at its
  // first step, so its Newton iterates (not the converged step, within the Newton tolerance)
  // differ from the run that kept the old one.
  void save_steps(IntegratorCache& out) const override {
    out.scalars = {cached_ ? 1.0 : 0.0, edited_ ? 1.0 : 0.0, cached_time_, power0_[0], power0_[1], power0_[2]};
    out.vectors = {q_end_, v_end_, a0_, f0_};
  }
  void restore_steps(const IntegratorCache& in) override {
    if (in.scalars.size() != 6 || in.vectors.size() != 4) return;
    cached_ = in.scalars[0] != 0.0;
    edited_ = in.scalars[1] != 0.0;
    cached_time_ = in.scalars[2];
    power0_ = Eigen::Vector3d(in.scalars[3], in.scalars[4], in.scalars[5]);
    q_end_ = in.vectors[0];
    v_end_ = in.vectors[1];
    a0_ = in.vectors[2];
    f0_ = in.vectors[3];
    for (IterationMatrix& m : matrices_) m.valid = false;
  }

 private:
  // True when the state differs from where the last step ended by more than a correction would
  // move it (a thousandth of the configuration's size).
  bool moved_far(const OdeState& s) const {
    if (q_end_.size() != s.q.size()) return true;
    const double size = std::max(q_end_.lpNorm<Eigen::Infinity>(), 1e-12);
    return (s.q - q_end_).lpNorm<Eigen::Infinity>() > 1e-3 * size;
  }

  // Newmark updates of q1_, v1_ from the start state and the trial a1_.
  void update_state(const OdeState& s, double h) {
    q1_ = s.q + h * s.qd + h * h * ((0.5 - beta_) * a0_ + beta_ * a1_);
    v1_ = s.qd + h * ((1.0 - gamma_) * a0_ + gamma_ * a1_);
  }

  // Newton iterations for a1; false when they do not converge.
  bool solve_step(OdeSystem& system, double t, double h, const OdeState& s) {
    // the configuration's size, or the step's own motion when the body sits at the origin at rest
    const double size = std::max({s.q.lpNorm<Eigen::Infinity>(), h * s.qd.lpNorm<Eigen::Infinity>(),
                                  h * h * a0_.lpNorm<Eigen::Infinity>(), 1e-12});
    const double tolerance = kNewtonTolerance * size;
    a1_ = a0_;  // predictor: the acceleration carries over
    iterate_failure_.clear();
    bool fresh_tangent = false;
    last_increment_ = std::numeric_limits<double>::infinity();
    double previous = std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      update_state(s, h);
      if (!evaluate_iterate(system, t + h, q1_, v1_, f1_, power1_)) return false;
      residual_ = a1_ - (1.0 + alpha_) * f1_ + alpha_ * f0_;
      last_residual_ = residual_.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(last_residual_)) return false;
      // a slowly converging or diverging old tangent is replaced at the current iterate
      IterationMatrix& m = matrices_[current_];
      if (!m.valid || (!fresh_tangent && iteration > 0 && last_increment_ > 0.25 * previous)) {
        if (!build_tangent(system, t, h)) return false;
        fresh_tangent = true;
      }
      const Eigen::VectorXd delta = m.factors.solve(-residual_);
      if (!delta.allFinite()) return false;
      a1_ += delta;
      previous = last_increment_;
      last_increment_ = beta_ * h * h * delta.lpNorm<Eigen::Infinity>();
      // round-off in the forces puts a floor under the increment that grows as h^2, so a large
      // step may not meet the fixed positional tolerance: once the increments stop shrinking
      // within a thousand times the tolerance, Newton has reached that floor and the step stands
      const bool stagnated = iteration >= 3 && last_increment_ > 0.5 * previous && last_increment_ <= 1e3 * tolerance;
      if (last_increment_ <= tolerance || stagnated) {
        update_state(s, h);
        system.derivative(t + h, q1_, v1_, f1_, power1_);
        // converged in a few iterations: the tangent is good for the next step too
        m.valid = iteration < 4;
        return f1_.allFinite();
      }
    }
    return false;
  }

  // The derivative at a Newton iterate or a perturbation of one; false when the system cannot
  // evaluate it (a constraint solve at a singular configuration). An iterate is not a state of
  // the run: one that lands where the mechanism locks says the step is too large for Newton, and
  // the failure asks for a smaller step instead of a change of geometry.
  bool evaluate_iterate(OdeSystem& system, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        Eigen::VectorXd& f, Eigen::Vector3d& power) {
    try {
      system.derivative(t, q, v, f, power);
      return true;
    } catch (const NumericalError& e) {
      iterate_failure_ = e.diagnostic().cause;
      return false;
    }
  }

  // The iteration matrix S = I - (1 + alpha) (beta h^2 f_q + gamma h f_qd) by coloured finite
  // differences about (q1_, v1_), then its factors (iteration_matrix_factors.h).
  bool build_tangent(OdeSystem& system, double t, double h) {
    const Eigen::Index n = q1_.size();
    // the pattern from the model at this iterate (contacts and the rank of the constraints may
    // change it); recoloured only when it changed. A system that cannot tell is perturbed once.
    if (system.jacobian_pattern(t + h, q1_, trial_pattern_)) {
      if (!pattern_valid_ || !(trial_pattern_ == pattern_)) use_pattern(trial_pattern_);
    } else if (!pattern_valid_ || pattern_.size() != n) {
      find_pattern(system, t, h);
    }
    const std::vector<int>& pattern_start = pattern_.start();
    const std::vector<int>& pattern_rows = pattern_.rows();
    const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
    const double q_scale = std::max(q1_.lpNorm<Eigen::Infinity>(), 1e-6);
    // the values go straight into S, whose compressed columns are the pattern's (with the diagonal)
    double* values = tangent_.valuePtr();
    Eigen::VectorXd step_of(n);
    for (const std::vector<int>& columns : colours_) {
      // perturb every column of this colour at once: a = a1 + eps_j e_j
      q_trial_ = q1_;
      v_trial_ = v1_;
      for (int j : columns) {
        const double eps = root_eps * std::max(std::abs(q1_[j]), q_scale) / (beta_ * h * h);
        step_of[j] = eps;
        q_trial_[j] += beta_ * h * h * eps;
        v_trial_[j] += gamma_ * h * eps;
      }
      if (!evaluate_iterate(system, t + h, q_trial_, v_trial_, f_trial_, power_trial_)) return false;
      for (int j : columns) {
        for (int k = pattern_start[j]; k < pattern_start[j + 1]; ++k) {
          const int i = pattern_rows[k];
          const double g = (f_trial_[i] - f1_[i]) / step_of[j];
          values[k] = (i == j ? 1.0 : 0.0) - (1.0 + alpha_) * g;
        }
      }
    }
    const Eigen::SparseMatrix<double>& matrix = tangent_;
    IterationMatrix& m = matrices_[current_];
    if (!m.factors.same_pattern(matrix)) {
      system.free_masses(free_mass_);
      m.factors.analyse(matrix, free_mass_);
    }
    if (!m.factors.factorize(matrix)) return false;
    m.valid = true;
    ++tangents_;
    return true;
  }

  // Which outputs each coordinate moves, by one perturbation per coordinate: a force
  // evaluation per coordinate, for systems that cannot give their pattern.
  void find_pattern(OdeSystem& system, double t, double h) {
    const Eigen::Index n = q1_.size();
    const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
    const double q_scale = std::max(q1_.lpNorm<Eigen::Infinity>(), 1e-6);
    trial_pattern_.reset(static_cast<int>(n));
    for (Eigen::Index j = 0; j < n; ++j) {
      const double eps = root_eps * std::max(std::abs(q1_[j]), q_scale) / (beta_ * h * h);
      q_trial_ = q1_;
      v_trial_ = v1_;
      q_trial_[j] += beta_ * h * h * eps;
      v_trial_[j] += gamma_ * h * eps;
      system.derivative(t + h, q_trial_, v_trial_, f_trial_, power_trial_);
      for (Eigen::Index i = 0; i < n; ++i)
        if (f_trial_[i] != f1_[i]) trial_pattern_.add(static_cast<int>(i), static_cast<int>(j));
    }
    trial_pattern_.finish();
    use_pattern(trial_pattern_);
  }

  // Takes the pattern and colours its columns so that columns of one colour share no row.
  void use_pattern(SparsityPattern& pattern) {
    std::swap(pattern_, pattern);
    colours_ = colour_columns(pattern_);
    const int n = pattern_.size();
    tangent_.resize(n, n);
    tangent_.resizeNonZeros(static_cast<Eigen::Index>(pattern_.nonzeros()));
    std::copy(pattern_.start().begin(), pattern_.start().end(), tangent_.outerIndexPtr());
    std::copy(pattern_.rows().begin(), pattern_.rows().end(), tangent_.innerIndexPtr());
    pattern_valid_ = true;
    for (IterationMatrix& m : matrices_) m.valid = false;
  }

  [[noreturn]] void fail(double t, double h) const {
    std::ostringstream cause;
    if (!iterate_failure_.empty())
      cause << "an HHT Newton iterate (a trial, not a state of the run) reached a configuration the system cannot "
               "evaluate at dt = "
            << h << " (" << iterate_failure_
            << "): the step is too large for the Newton iterations, or the motion meets a singular position within it";
    else
      cause << "the HHT Newton iterations did not converge in " << kMaxIterations << " iterations (residual "
            << last_residual_ << ", last position increment " << last_increment_ << ") at dt = " << h;
    std::ostringstream remedy;
    remedy << "lower solver.dt (e.g. to " << 0.25 * h << ")";
    if (!iterate_failure_.empty())
      remedy << "; if the mechanism passes a toggle (singular) position, change its geometry or driver";
    throw NumericalError({"Newton residual", accepted_ + 1, t + h, cause.str(), remedy.str()});
  }

  double alpha_, gamma_, beta_;

  // the start of the step
  bool cached_ = false, edited_ = false;
  double cached_time_ = 0.0;
  Eigen::VectorXd q_end_, v_end_;  // the state the last step ended in
  Eigen::VectorXd a0_, f0_;
  Eigen::Vector3d power0_ = Eigen::Vector3d::Zero();
  // the iterate
  Eigen::VectorXd a1_, q1_, v1_, f1_, residual_;
  Eigen::Vector3d power1_ = Eigen::Vector3d::Zero();
  double last_residual_ = 0.0, last_increment_ = 0.0;
  std::string iterate_failure_;  // why the last iterate could not be evaluated, for the failure
  // finite-difference scratch
  Eigen::VectorXd q_trial_, v_trial_, f_trial_;
  Eigen::Vector3d power_trial_ = Eigen::Vector3d::Zero();
  // sparsity pattern (rows of each column) and column colours; the pattern last asked for
  bool pattern_valid_ = false;
  SparsityPattern pattern_, trial_pattern_;
  std::vector<std::vector<int>> colours_;
  Eigen::SparseMatrix<double> tangent_;  // S, in the pattern's compressed columns
  Eigen::VectorXd free_mass_;            // the system's free masses, which scale S's rows
  // The factorised iteration matrices of the last two step sizes. A run that lands on its output
  // times alternates between its dt and the shorter step that reaches the next output (dt =
  // 7.5e-5 s, output every 2e-4 s: two full steps and one of 5e-5 s); with one matrix, every
  // change of step size rebuilt it, at 88% of the steps of the flexible slider-crank.
  struct IterationMatrix {
    IterationMatrixFactors factors;
    double h = 0.0;
    long last_used = -1;
    bool valid = false;
  };
  std::array<IterationMatrix, 2> matrices_;
  size_t current_ = 0;  // the current step's
  long tangents_ = 0;

  // The matrix for step size h (the same to a billionth, as a step that lands on an output time
  // is computed from the clock), or the one used longest ago, emptied for h.
  size_t matrix_for(double h) {
    const auto same = [h](const IterationMatrix& m) { return std::abs(m.h - h) <= 1e-9 * h; };
    size_t k = 0;
    while (k < matrices_.size() && !same(matrices_[k])) ++k;
    if (k == matrices_.size()) {
      k = matrices_[0].last_used <= matrices_[1].last_used ? 0 : 1;
      matrices_[k].h = h;
      matrices_[k].valid = false;
    }
    matrices_[k].last_used = accepted_;
    return k;
  }
};

}  // namespace

std::unique_ptr<Integrator> make_hht(double alpha) {
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) throw std::invalid_argument("HHT alpha must lie in [-1/3, 0]");
  return std::make_unique<Hht>(alpha);
}

std::unique_ptr<Integrator> make_hht(const SolverDef& solver) { return make_hht(solver.hht_alpha); }

}  // namespace periflex
