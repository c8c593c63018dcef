// The equations of motion of the assembled model: generalised forces, the constraint solve
// [M Phi_q^T; Phi_q 0][qdd; lambda] = [g; gamma] over the constrained coordinates only
// (unconstrained ones get qdd = g / m directly), imposed particle motions, the Baumgarte
// terms, and the mass-weighted projections of positions and velocities onto the constraints.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "model/system_model.h"
#include "solve/condensed_attachments.h"
#include "solve/dense_constraint_solver.h"
#include "solve/integrator.h"
#include "solve/kkt_solver.h"
#include "solve/sim_state.h"

namespace periflex {

// A spring from a body point, or from a patch of particles, to a point the mouse holds
// (resolved indices). Each held particle is pulled towards the target plus its offset (its place
// relative to the grabbed particle at the grab), so the patch moves as one without collapsing.
struct MouseSpringForce {
  BodyPoint point;                        // rigid grab point (point.body >= 0), or
  std::vector<int> particle_coordinates;  // index of each held particle's x in q
  std::vector<Vec2> offsets;              // per held particle
  std::vector<double> particle_stiffness, particle_damping;  // per held particle
  Vec2 target = Vec2::Zero();
  double stiffness = 0.0, damping = 0.0;  // rigid point; for a patch, the sums over it
  int grabbed_body = -1, grabbed_particle = -1;  // what was grabbed (MouseSpring's indices)
  // The point pulled towards travels from `from` (where it was at time `since`) to `target` at
  // most at `speed` [m/s] (0: at once), so a pointer that jumps does not fling a stiff patch.
  Vec2 from = Vec2::Zero();
  double since = 0.0, speed = 0.0;
  Vec2 target_at(double t) const {
    const Vec2 way = target - from;
    const double length = way.norm(), reach = speed * std::max(0.0, t - since);
    return speed <= 0.0 || reach >= length ? target : Vec2(from + way * (reach / length));
  }
  // Energy the spring holds at (t, q): what it can still give to what it holds.
  double stored_energy(double t, const Eigen::VectorXd& q) const;
};

class Dynamics final : public OdeSystem {
 public:
  explicit Dynamics(SystemModel& model);

  // At (t, q0): finds dependent constraint rows (left out of the solves) and checks that every
  // coordinate's motion is determined. Throws InputError naming an undetermined body, or the
  // constraints of a dependency that involves an attachment and whose drivers or imposed
  // motions contradict each other (they cannot all hold once the motion starts).
  void analyse(double t);
  // Large systems: the rank of the small system of the rigid and virtual bodies at (t, q)
  // (joints, drivers, and the attachment rows that tie bodies together through shared or
  // imposed particles); when it differs from the rows left out now, the dependent rows are
  // derived again at q. Returns true when they changed. Small systems do this at every solve.
  bool update_rank(double t, const Eigen::VectorXd& q);
  // Global rows dropped as dependent, and the names of the blocks they came from.
  const std::vector<int>& dropped_rows() const { return dropped_; }
  std::vector<std::string> dropped_blocks() const;
  int active_rows() const { return static_cast<int>(active_.size()); }
  // Equations independent at t0 (all rows less the dependent ones).
  int independent_rows() const { return model_.constraint_rows - static_cast<int>(initial_dropped_); }
  // Small rigid systems (no eliminated attachments, at most kDenseRows equations): every
  // solve is dense and finds the rank of the Jacobian again (see dense_constraint_solver.h),
  // so all rows stay active and a row is left out only while it depends on the others.
  // Large systems find it at every step (update_rank).
  bool monitors_rank() const { return dense_ || !monitored_rows_.empty(); }
  // Whether the system is solved dense (small rigid systems).
  bool dense() const { return dense_; }
  // Rows left out of the last acceleration solve as dependent (rank monitoring), the
  // smallest scaled pivot of that solve, and how often the set of left-out rows changed.
  const std::vector<int>& dependent_now() const { return dense_ ? dense_acceleration_.dependent() : dropped_; }
  double smallest_pivot() const { return dense_ ? dense_acceleration_.smallest_pivot() : 1.0; }
  long rank_changes() const { return rank_changes_; }
  // The rows left out now and the rank history, for saving a state; restoring leaves out the
  // same rows (rebuilding what depends on them only when they differ).
  void save_rank(RankState& out) const;
  void restore_rank(const RankState& in);
  // Names of the blocks of the given global rows.
  std::vector<std::string> blocks_of(const std::vector<int>& rows) const;
  static constexpr int kDenseRows = 64;
  static constexpr int kDenseCoordinates = 192;
  // Scaled pivot below which a row counts as dependent while running: a row within about
  // 0.06 degree of the others' span (in the mass metric) is left out rather than solved with an
  // amplification above 1e3. Near a singular position the Jacobian's smallest pivot goes to
  // zero in proportion to the distance from it; stages of a step that land that close would
  // otherwise amplify the integration error by its inverse and carry the state onto another
  // branch. Measured on the double four-bar (docs/solver.md): 1e-5 switches branch at
  // dt = 1e-4; 1e-3 keeps every step size from 2.5e-2 to 1.25e-5 on the physical branch; 1e-2
  // too, with a larger error from the steps spent without the row.
  static constexpr double kRankThreshold = 1e-3;
  // Angles of zero-inertia bodies that no constraint sees and no force turns (see
  // held_rotations.h): out of the equations, held at their initial value.
  const std::vector<int>& held_rotations() const { return held_; }
  int constrained_coordinates() const { return static_cast<int>(constrained_.size()); }
  bool has_constraints() const { return !active_.empty(); }

  void set_correction(const CorrectionDef& correction) { correction_ = correction; }
  // Whether analyse() may solve rigid-flexible joints by elimination (default true; the full
  // augmented system gives the same answer, slower; for tests and comparisons).
  void set_condense_attachments(bool enabled) { condense_ = enabled; }
  const CorrectionDef& correction() const { return correction_; }
  void set_mouse_spring(const std::optional<MouseSpringForce>& spring) { mouse_ = spring; }
  // The spring set (to move its target without resolving it again).
  std::optional<MouseSpringForce>& mouse_spring() { return mouse_; }

  // OdeSystem: accelerations and the dissipated / external / driver powers.
  void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override;
  // The pattern of d qdd / d(q, qd) from the model (jacobian_pattern.cpp): the force elements'
  // couplings, and what the constraint solve couples. False when a force element cannot tell.
  bool jacobian_pattern(double t, const Eigen::VectorXd& q, SparsityPattern& pattern) override;
  // The masses of the coordinates neither constrained nor imposed, 0 for the others.
  void free_masses(Eigen::VectorXd& mass) override;
  // Multipliers of the active rows from the last derivative() call.
  const Eigen::VectorXd& multipliers() const { return lambda_; }
  // The multiplier of global constraint row `row` from that call (0 for a row left out).
  double row_multiplier(int row) const {
    if (row < 0 || row >= static_cast<int>(active_index_.size())) return 0.0;
    const int a = active_index_[row];
    return a >= 0 && a < lambda_.size() ? lambda_[a] : 0.0;
  }

  // Writes the imposed q and qd of the prescribed particle coordinates at t.
  void impose_prescribed(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const;
  // Newton iterations on Phi(q, t) = 0 with the mass-weighted least change; returns max |Phi| after.
  double project_positions(double t, Eigen::VectorXd& q, double tolerance, int max_iterations);
  // SHAKE: Newton on Phi(q + W^-1 Phi_q(q_start)^T mu, t) = 0, the correction along the
  // constraint normals at the start of the step (what keeps symplectic Euler and Verlet
  // symplectic with constraints); the nearest-point projection above for large systems.
  double project_positions_from(double t, const Eigen::VectorXd& q_start, Eigen::VectorXd& q, double tolerance,
                                int max_iterations);
  // Mass-weighted least change of qd with Phi_q qd + Phi_t = 0; returns max |change|.
  double project_velocities(double t, const Eigen::VectorXd& q, Eigen::VectorXd& qd);

  // max |Phi| and max |Phi_q qd + Phi_t| over every row, the dependent ones included.
  double position_violation(double t, const Eigen::VectorXd& q);
  double velocity_violation(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  // Blocks whose active rows are (nearly) dependent at (t, q): a rank-revealing QR of the
  // Jacobian with pivots below relative_threshold counted as zero. Empty when of full rank.
  std::vector<std::string> nearly_dependent_blocks(double t, const Eigen::VectorXd& q, double relative_threshold);
  // Name of the block with the largest |Phi| at (t, q).
  std::string worst_constraint(double t, const Eigen::VectorXd& q);

  // Rigid-flexible joints solved by elimination (see condensed_attachments.h): how many
  // coordinates and equations stay in the matrix.
  int reduced_coordinates() const { return static_cast<int>(reduced_cols_.size()); }
  int reduced_rows() const { return static_cast<int>(reduced_rows_.size()); }

  // Wall-clock seconds in force evaluation and in the constraint solve (estimated from one
  // evaluation in kTimedEvery).
  double force_seconds() const { return force_seconds_; }
  double constraint_seconds() const { return constraint_seconds_; }
  // Times the augmented matrix pattern was analysed (stays 1 for a fixed constraint set).
  int pattern_analyses() const { return kkt_.analyses(); }

 private:
  // Jacobian of the active rows at (t, q): local triplets over the constrained coordinates,
  // and separately the entries on prescribed coordinates (global column).
  void assemble_jacobian(double t, const Eigen::VectorXd& q);
  void residual_all(double t, const Eigen::VectorXd& q);   // phi_all_
  void time_derivative_all(double t, const Eigen::VectorXd& q);  // phi_t_all_
  // The Jacobian of the rows that stay in the matrix, over the coordinates that stay
  // (reduced_j_, and prescribed_j_ with reduced rows), and the eliminated joints at q.
  void assemble_reduced(double t, const Eigen::VectorXd& q);
  // nu_all_ = Phi_q qd + Phi_t by global row (after assemble_reduced and time_derivative_all).
  void velocity_residual_all(const Eigen::VectorXd& qd);
  // Solves W z + Phi_q^T mu = a, Phi_q z = e with W = diag(w) over the constrained coordinates,
  // the eliminated joints condensed (after assemble_reduced). w and a by global coordinate
  // (a null: zero), e by global row; z receives the constrained coordinates (global index) and
  // x_ the reduced solution. False when the matrix is singular.
  bool solve_constrained(const Eigen::VectorXd& w, const double* a, const double* e, KktSolver& solver,
                         Eigen::VectorXd& z);
  bool solve_dense(const Eigen::VectorXd& w, const double* a, const double* e, DenseConstraintSolver& solver,
                   Eigen::VectorXd& z);
  // max |Phi| over the rows the last projection solve kept (after residual_all).
  double selected_violation() const;
  [[noreturn]] void throw_singular(double t, const Eigen::VectorXd& q, const std::string& during);
  // Leaves out the given global rows (increasing) and rebuilds what depends on the active set:
  // the eliminated attachments, the reduced rows and columns, the multipliers.
  void select_rows(const std::vector<int>& dropped);
  // The rows the large-system rank monitor watches, from the attachment structure at (t, q).
  void choose_monitored_rows(double t, const Eigen::VectorXd& q);
  // Dependent rows of a Jacobian over the constrained coordinates, particle columns eliminated
  // first (see redundancy.h).
  std::vector<int> dependent_active_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) const;
  // Refuses a dependency with contradicting right-hand sides that involves an attachment.
  void refuse_conflict(const std::vector<int>& rows) const;
  const std::string& block_of_row(int row) const;

  SystemModel& model_;
  CorrectionDef correction_;
  SparsityPattern force_pattern_;  // scratch of jacobian_pattern
  std::optional<MouseSpringForce> mouse_;

  // coordinate classes
  std::vector<int> constrained_;  // global indices, in local order
  std::vector<int> local_;        // global -> local (-1 when not constrained)
  std::vector<int> free_;         // unconstrained, not prescribed, not held
  std::vector<int> held_;         // zero-inertia angles held at their initial value
  std::vector<int> dropped_;      // global rows
  size_t initial_dropped_ = 0;    // dependent rows at t0
  // large systems: rows the rank monitor watches (increasing), the attachment rows that
  // always depend on them (shared particles of bodies already tied together), and whether
  // each local column is a particle coordinate (eliminated first in the rank analysis)
  std::vector<int> monitored_rows_, structural_dropped_;
  std::vector<char> particle_column_;
  Eigen::VectorXd selection_c_, monitor_weight_;
  std::vector<int> active_;       // global rows kept, in order
  std::vector<int> active_index_; // global row -> active index (-1 dropped)
  std::vector<char> active_is_driver_;  // per active row
  Eigen::VectorXd mass_c_, weight_c_;  // masses and projection weights of the constrained coordinates
  Eigen::VectorXd weight_;             // projection weights by global coordinate
  Eigen::VectorXd selection_;          // the metric of the rank decision (dense path)
  Eigen::VectorXd inverse_mass_;       // 1 / m by global coordinate (0 where m = 0)
  bool has_gravity_ = true;

  // the reduced system: what stays in the matrix once the eliminated joints are condensed
  CondensedAttachments condensed_;
  bool condense_ = true;
  std::vector<int> reduced_col_;   // global coordinate -> reduced column (-1: not in the matrix)
  std::vector<int> reduced_cols_;  // reduced column -> global coordinate
  std::vector<int> reduced_rows_;  // reduced row -> active row
  Triplets reduced_j_, coupling_;
  Eigen::VectorXd diag_, select_, e_all_, nu_all_, dz_;
  std::vector<int> active_index_work_;

  // work arrays
  Triplets all_, local_j_, prescribed_j_;
  Eigen::VectorXd phi_all_, phi_t_all_, gamma_all_;
  Eigen::VectorXd g_, q_work_, qd_work_, rhs_, x_, lambda_;
  KktSolver kkt_, projection_kkt_;
  // the dense path with rank monitoring (small rigid systems)
  bool dense_ = false;
  DenseConstraintSolver dense_acceleration_, dense_projection_;
  std::vector<int> last_dependent_;
  Eigen::MatrixXd start_j_, shake_matrix_;
  Eigen::VectorXd shake_rhs_;
  Eigen::PartialPivLU<Eigen::MatrixXd> shake_lu_;
  long rank_changes_ = 0;

  static constexpr long kTimedEvery = 8;
  long evaluations_ = 0;
  double force_seconds_ = 0.0, constraint_seconds_ = 0.0;
};

}  // namespace periflex
