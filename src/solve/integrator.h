// Time integrators behind one small interface, so the stepper does not care which one runs
// (and an implicit HHT / generalised-alpha can be added later beside them).
//
// The state is the second-order system q' = qd, qd' = qdd(t, q, qd) plus three running
// integrals of power (dissipated, external, driver work) that the energy balance needs;
// the integrator advances them with the same rule as q and qd.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/sparsity_pattern.h"
#include "scene/integrator_catalogue.h"
#include "scene/scene_def.h"
#include "solve/sim_state.h"

namespace periflex {

// Indices of OdeState::work.
enum WorkIndex : int { kWorkDissipated = 0, kWorkExternal = 1, kWorkDriver = 2 };

struct OdeState {
  Eigen::VectorXd q, qd;
  Eigen::Vector3d work = Eigen::Vector3d::Zero();  // integrals of the powers, see WorkIndex
};

// The right-hand side the integrators call: accelerations and the three powers.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd,
                          Eigen::Vector3d& power) = 0;
  // The structure of d qdd / d(q, qd) at (t, q): the pairs (row, column) a change of q or qd in
  // the column can move, into pattern (reset to the size of q and finished). False when the
  // system cannot tell; an implicit integrator then finds it by perturbing every coordinate.
  virtual bool jacobian_pattern(double /*t*/, const Eigen::VectorXd& /*q*/, SparsityPattern& /*pattern*/) { return false; }
  // The mass of each coordinate whose acceleration is its force over its mass (qdd_i = g_i / m_i:
  // neither constrained nor imposed), 0 for the others, into mass (sized to q); left empty by a
  // system that cannot tell. An implicit integrator scales those rows of its iteration matrix by
  // them, which makes their block symmetric for conservative forces (iteration_matrix_factors.h).
  virtual void free_masses(Eigen::VectorXd& mass) { mass.resize(0); }
};

class Integrator {
 public:
  explicit Integrator(IntegratorKind kind) : traits_(integrator_traits(kind)) {}
  virtual ~Integrator() = default;
  // Its row of the catalogue: name, order and traits (scene/integrator_catalogue.h).
  const IntegratorTraits& traits() const { return traits_; }
  // Name as written in scene files and on the command line.
  const std::string& name() const { return traits_.name; }
  // Global order of accuracy.
  int order() const { return traits_.order; }
  // Explicit integrators are bound by the critical step of stiff (peridynamic) parts.
  bool is_explicit() const { return traits_.is_explicit; }
  // Symplectic integrators (symplectic Euler, Verlet): a position projection after their
  // step also corrects the velocity by the same change over the step (SHAKE / RATTLE).
  bool is_symplectic() const { return traits_.is_symplectic; }
  // Adaptive integrators choose their own internal steps inside each call to step().
  bool is_adaptive() const { return traits_.is_adaptive; }
  // Advances s from t to t + dt.
  virtual void step(OdeSystem& system, double t, double dt, OdeState& s) = 0;
  // Forgets data cached from the previous step (the state was changed from outside).
  virtual void reset() {}
  // What the next step reads from earlier ones (none for the single-step methods), and its
  // return: restoring the cache an integrator of the same name saved makes its next step
  // repeat bit for bit; any other cache resets it.
  void save_cache(IntegratorCache& out) const {
    out.name = name();
    out.scalars.clear();
    out.vectors.clear();
    save_steps(out);
    out.accepted = accepted_;
    out.rejected = rejected_;
  }
  void restore_cache(const IntegratorCache& in) {
    reset();
    if (in.name != name()) return;
    restore_steps(in);
    accepted_ = in.accepted;
    rejected_ = in.rejected;
  }
  // Internal steps taken and rejected so far (adaptive integrators; others count steps).
  long accepted_steps() const { return accepted_; }
  long rejected_steps() const { return rejected_; }

 protected:
  // the integrator's own part of the cache (scalars and vectors in an order of its own)
  virtual void save_steps(IntegratorCache&) const {}
  virtual void restore_steps(const IntegratorCache&) {}
  long accepted_ = 0, rejected_ = 0;

 private:
  const IntegratorTraits& traits_;
};

// Builds the integrator `name` (a row of the catalogue, integrator_names()); rtol / atol from the
// solver definition. Throws InputError naming the choices for an unknown name.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const SolverDef& solver);

}  // namespace periflex
