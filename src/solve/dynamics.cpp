#include "solve/dynamics.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "core/error.h"
#include "solve/held_rotations.h"
#include "solve/redundancy.h"

namespace periflex {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }
}  // namespace

double MouseSpringForce::stored_energy(double t, const Eigen::VectorXd& q) const {
  const Vec2 aim = target_at(t);
  double energy = 0.0;
  if (point.body >= 0) energy += 0.5 * stiffness * (aim - point.position(q)).squaredNorm();
  for (size_t k = 0; k < particle_coordinates.size(); ++k) {
    const int c = particle_coordinates[k];
    energy += 0.5 * particle_stiffness[k] * (aim + offsets[k] - Vec2(q[c], q[c + 1])).squaredNorm();
  }
  return energy;
}

Dynamics::Dynamics(SystemModel& model) : model_(model) {}

const std::string& Dynamics::block_of_row(int row) const {
  const ConstraintBlock* found = &model_.constraints.front();
  for (const auto& block : model_.constraints) {
    if (block.first_row <= row) found = &block;
  }
  return found->constraint->name();
}

std::vector<std::string> Dynamics::dropped_blocks() const { return blocks_of(dropped_); }

std::vector<std::string> Dynamics::blocks_of(const std::vector<int>& rows) const {
  std::vector<std::string> names;
  for (int row : rows) {
    const std::string& name = block_of_row(row);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

void Dynamics::analyse(double t) {
  const int n = model_.coordinate_count;
  const Eigen::VectorXd& q = model_.q0;

  // constrained coordinates: any a constraint block depends on, unless prescribed
  std::set<int> touched;
  std::vector<int> coords;
  for (const auto& block : model_.constraints) {
    coords.clear();
    block.constraint->coordinates(coords);
    for (int c : coords) {
      if (!model_.is_prescribed[c]) touched.insert(c);
    }
  }
  // zero-inertia rotations no constraint sees leave the equations, held at their angle
  held_ = find_held_rotations(model_, t);
  for (int c : held_) touched.erase(c);
  constrained_.assign(touched.begin(), touched.end());
  local_.assign(n, -1);
  for (size_t k = 0; k < constrained_.size(); ++k) local_[constrained_[k]] = static_cast<int>(k);
  free_.clear();
  for (int c = 0; c < n; ++c) {
    const bool held = std::find(held_.begin(), held_.end(), c) != held_.end();
    if (local_[c] < 0 && !model_.is_prescribed[c] && !held) free_.push_back(c);
  }

  // a coordinate no constraint acts on needs mass of its own
  for (int c : free_) {
    if (model_.mass[c] > 0.0) continue;
    const SourceLocation where = c < model_.rigid_coordinates ? model_.bodies[c / 3].where : SourceLocation{};
    const char* which = (c < model_.rigid_coordinates && c % 3 == 2) ? "inertia" : "mass";
    throw InputError(where, "motion undetermined: " + model_.coordinate_owner(c) + " has zero " + which +
                                " and no constraint acts on it; give it " + which + " or attach it");
  }

  // dependent rows at t0: the particle coordinates are eliminated first (rows of the
  // rigid-flexible joints), so the rank-revealing QR sees only the small system of the bodies
  const int rows = model_.constraint_rows;
  const int nc0 = static_cast<int>(constrained_.size());
  particle_column_.assign(nc0, 0);
  for (int k = 0; k < nc0; ++k) particle_column_[k] = constrained_[k] >= model_.rigid_coordinates;
  active_index_.assign(rows, -1);
  for (int r = 0; r < rows; ++r) active_index_[r] = r;
  active_.resize(rows);
  for (int r = 0; r < rows; ++r) active_[r] = r;
  dropped_.clear();
  std::vector<int> dropped;
  if (rows > 0) {
    assemble_jacobian(t, q);
    Eigen::SparseMatrix<double> j(rows, nc0);
    j.setFromTriplets(local_j_.begin(), local_j_.end());
    // what the drivers and imposed motions ask of the velocities, Phi_t + Phi_q(imposed) qd:
    // a dependency must ask the same of its rows, or the motion cannot start
    time_derivative_all(t, q);
    Eigen::VectorXd rates = phi_t_all_;
    Eigen::VectorXd q_imposed = q, qd_imposed = model_.qd0;
    impose_prescribed(t, q_imposed, qd_imposed);
    for (const auto& e : prescribed_j_) rates[e.row()] += e.value() * qd_imposed[e.col()];
    RowAnalysisOptions options;
    options.eliminable = particle_column_;
    options.rhs = &rates;
    const RowDependence found = find_dependent_rows(j, options);
    if (!found.conflicting.empty()) refuse_conflict(found.conflicting);
    dropped = found.dependent;
  }
  initial_dropped_ = dropped.size();
  dropped_ = dropped;
  for (int r : dropped) active_index_[r] = -1;
  active_.clear();
  for (int r = 0, a = 0; r < rows; ++r) {
    if (active_index_[r] >= 0) {
      active_index_[r] = a++;
      active_.push_back(r);
    }
  }

  // masses of the constrained coordinates; projection weights floor zero masses at a small
  // fraction of the typical mass of the same kind, so massless bodies follow but stay defined
  const int nc = static_cast<int>(constrained_.size());
  mass_c_.resize(nc);
  weight_c_.resize(nc);
  double mass_sum = 0.0, inertia_sum = 0.0;
  int mass_count = 0, inertia_count = 0;
  for (int c = 0; c < n; ++c) {
    const bool rotational = c < model_.rigid_coordinates && c % 3 == 2;
    if (model_.mass[c] <= 0.0) continue;
    (rotational ? inertia_sum : mass_sum) += model_.mass[c];
    ++(rotational ? inertia_count : mass_count);
  }
  const double mass_ref = mass_count ? mass_sum / mass_count : 1.0;
  const double inertia_ref =
      inertia_count ? inertia_sum / inertia_count : mass_ref * model_.length_scale * model_.length_scale;
  for (int k = 0; k < nc; ++k) {
    const int c = constrained_[k];
    const bool rotational = c < model_.rigid_coordinates && c % 3 == 2;
    mass_c_[k] = model_.mass[c];
    weight_c_[k] = model_.mass[c] > 0.0 ? model_.mass[c] : 1e-6 * (rotational ? inertia_ref : mass_ref);
  }

  // massless constrained coordinates need the constraints to fix them: rank of J over them
  std::vector<int> massless;
  for (int k = 0; k < nc; ++k) {
    if (mass_c_[k] <= 0.0) massless.push_back(k);
  }
  if (!massless.empty() && !active_.empty()) {
    assemble_jacobian(t, q);
    Eigen::SparseMatrix<double> j(active_rows(), nc);
    j.setFromTriplets(local_j_.begin(), local_j_.end());
    j.makeCompressed();
    // only the massless columns, dense: few of them, however many rows
    auto rank_of = [&](const std::vector<int>& cols) {
      Eigen::MatrixXd sub = Eigen::MatrixXd::Zero(j.rows(), static_cast<Eigen::Index>(cols.size()));
      for (size_t k = 0; k < cols.size(); ++k) sub.col(static_cast<Eigen::Index>(k)) = Eigen::VectorXd(j.col(cols[k]));
      return column_rank(sub);
    };
    if (rank_of(massless) < static_cast<int>(massless.size())) {
      // name the bodies that are undetermined on their own, else all massless ones
      std::vector<std::string> names;
      std::vector<int> all_owners;
      for (int k : massless) {
        const std::string owner = model_.coordinate_owner(constrained_[k]);
        if (std::find(names.begin(), names.end(), owner) == names.end()) names.push_back(owner);
      }
      std::vector<std::string> alone;
      for (const auto& owner : names) {
        std::vector<int> cols;
        for (int k : massless) {
          if (model_.coordinate_owner(constrained_[k]) == owner) cols.push_back(k);
        }
        if (rank_of(cols) < static_cast<int>(cols.size())) alone.push_back(owner);
      }
      const auto& list = alone.empty() ? names : alone;
      std::string text;
      for (const auto& s : list) text += (text.empty() ? "" : ", ") + s;
      SourceLocation where;
      const int c0 = constrained_[massless.front()];
      if (c0 < model_.rigid_coordinates) where = model_.bodies[c0 / 3].where;
      throw InputError(where, "motion undetermined: " + text +
                                  " has zero mass or inertia and the constraints do not fix its motion; give "
                                  "it mass and inertia or constrain it further");
    }
  }
  has_gravity_ = !model_.gravity_force.isZero(0.0);
  inverse_mass_ = model_.mass.unaryExpr([](double m) { return m > 0.0 ? 1.0 / m : 0.0; });
  weight_ = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < nc; ++k) weight_[constrained_[k]] = weight_c_[k];
  // the metric the rank is judged in: masses, raised to a hundredth of the typical mass of their
  // kind (a massless or nearly massless body would otherwise dominate the scaled rows and make
  // independent joints look parallel)
  selection_ = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < nc; ++k) {
    const int c = constrained_[k];
    const bool rotational = c < model_.rigid_coordinates && c % 3 == 2;
    selection_[c] = std::max(model_.mass[c], 1e-2 * (rotational ? inertia_ref : mass_ref));
  }

  // the metric of the large systems' rank monitor: a body carries the particles it holds
  // (a virtual body's mass is that of its particles), so its columns weigh what moves with it
  Eigen::VectorXd carried = Eigen::VectorXd::Zero(n);
  for (const Attachment& attachment : model_.attachments) {
    const RigidFlexibleJoint& joint = *attachment.joint;
    if (joint.body() < 0) continue;
    const int b = joint.body();
    for (int p = 0; p < joint.particle_count(); ++p) {
      const double mp = model_.mass[joint.particle_coordinates()[p]];
      carried[3 * b] += mp;
      carried[3 * b + 1] += mp;
      carried[3 * b + 2] += mp * joint.local_position(p).squaredNorm();
    }
  }
  selection_c_.resize(nc);
  for (int k = 0; k < nc; ++k) {
    const int c = constrained_[k];
    selection_c_[k] = std::max(selection_[c], model_.mass[c] + carried[c]);
  }

  // attachments solved by elimination, and what stays in the matrix; a small rigid system is
  // solved dense with its rank found at every solve: every row stays active, and the rows
  // dependent at t0 are only left out while they stay dependent
  dense_ = false;
  select_rows(dropped);
  dense_ = condensed_.empty() && rows > 0 && rows <= kDenseRows && nc <= kDenseCoordinates;
  if (dense_) {
    select_rows(dropped);
    dense_acceleration_.resize(static_cast<int>(reduced_cols_.size()), static_cast<int>(reduced_rows_.size()));
    dense_projection_.resize(static_cast<int>(reduced_cols_.size()), static_cast<int>(reduced_rows_.size()));
    dense_acceleration_.set_late_rows(dropped_);
    dense_projection_.set_late_rows(dropped_);
    last_dependent_ = dropped_;
    last_dependent_.reserve(rows);  // copied into at each change of rank: no allocation then
  }
  rank_changes_ = 0;
  choose_monitored_rows(t, q);
}

void Dynamics::save_rank(RankState& out) const {
  out.dropped = dropped_;
  out.last_dependent = last_dependent_;
  out.rank_changes = rank_changes_;
}

void Dynamics::restore_rank(const RankState& in) {
  for (int r : in.dropped) {
    if (r < 0 || r >= model_.constraint_rows) throw std::invalid_argument("state: a dropped row outside the model");
  }
  if (in.dropped != dropped_) select_rows(in.dropped);
  // copied into the reserved buffer: no allocation at the next change of rank
  last_dependent_.assign(in.last_dependent.begin(), in.last_dependent.end());
  rank_changes_ = in.rank_changes;
}

void Dynamics::select_rows(const std::vector<int>& dropped) {
  const int n = model_.coordinate_count, rows = model_.constraint_rows;
  dropped_ = dropped;
  active_index_.assign(rows, 0);
  for (int r : dropped_) active_index_[r] = -1;
  active_.clear();
  for (int r = 0, a = 0; r < rows; ++r) {
    if (active_index_[r] >= 0) {
      active_index_[r] = a++;
      active_.push_back(r);
    }
  }
  condensed_.build(model_, active_index_, condense_ && !dense_);
  if (dense_) {
    active_.resize(rows);
    for (int r = 0; r < rows; ++r) active_[r] = active_index_[r] = r;
  }
  reduced_col_.assign(n, -1);
  reduced_cols_.clear();
  for (int c : constrained_) {
    if (condensed_.coordinate_condensed(c)) continue;
    reduced_col_[c] = static_cast<int>(reduced_cols_.size());
    reduced_cols_.push_back(c);
  }
  reduced_rows_.clear();
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    if (condensed_.block_condensed(k)) continue;
    const ConstraintBlock& block = model_.constraints[k];
    for (int r = 0; r < block.constraint->rows(); ++r) {
      const int a = active_index_[block.first_row + r];
      if (a >= 0 && !condensed_.row_condensed(block.first_row + r)) reduced_rows_.push_back(a);
    }
  }
  std::sort(reduced_rows_.begin(), reduced_rows_.end());

  lambda_ = Eigen::VectorXd::Zero(active_rows());
  active_is_driver_.assign(active_rows(), 0);
  for (const auto& block : model_.constraints) {
    if (!block.constraint->is_driver()) continue;
    for (int r = 0; r < block.constraint->rows(); ++r) {
      const int a = active_index_[block.first_row + r];
      if (a >= 0) active_is_driver_[a] = 1;
    }
  }
}

void Dynamics::choose_monitored_rows(double t, const Eigen::VectorXd& q) {
  monitored_rows_.clear();
  structural_dropped_.clear();
  if (dense_ || model_.constraint_rows == 0) return;
  // the attachment rows alone: with the particle columns eliminated, the rows left tie bodies
  // together through shared particles (or to imposed particles); the dependent ones among
  // them depend on the others at every position (rigid bodies sharing points stay so), the
  // independent ones are watched with the joints and drivers
  const int rows = model_.constraint_rows, nc = static_cast<int>(constrained_.size());
  std::vector<char> is_attachment(rows, 0);
  std::vector<int> particle_of_row(rows, -1);
  Triplets entries;
  for (const auto& block : model_.constraints) {
    if (block.origin != ConstraintBlock::Origin::kAttachment) continue;
    all_.clear();
    block.constraint->jacobian(q, t, block.first_row, all_);
    for (const auto& e : all_) {
      if (local_[e.col()] >= 0) entries.emplace_back(e.row(), local_[e.col()], e.value());
    }
    for (int r = 0; r < block.constraint->rows(); ++r) is_attachment[block.first_row + r] = 1;
  }
  for (const Attachment& attachment : model_.attachments) {
    const std::vector<int>& particles = attachment.joint->particle_coordinates();
    for (int r = 0; r < attachment.joint->rows(); ++r) particle_of_row[attachment.first_row + r] = particles[r / 2];
  }
  std::vector<char> watched(rows, 0);
  for (const auto& block : model_.constraints) {
    if (block.origin == ConstraintBlock::Origin::kAttachment) continue;
    for (int r = 0; r < block.constraint->rows(); ++r) watched[block.first_row + r] = 1;
  }
  if (!entries.empty()) {
    Eigen::SparseMatrix<double> j(rows, nc);
    j.setFromTriplets(entries.begin(), entries.end());
    RowAnalysisOptions options;
    options.eliminable = particle_column_;
    const RowDependence found = find_dependent_rows(j, options);
    std::vector<char> dependent(rows, 0), pivot(rows, 0);
    for (int r : found.dependent) dependent[r] = is_attachment[r];
    for (int r : found.pivots) pivot[r] = 1;
    for (int r = 0; r < rows; ++r) {
      if (dependent[r]) structural_dropped_.push_back(r);
    }
    // the independent rows that are not pivots, and the other rows on their particles
    std::vector<char> particle_watched(model_.coordinate_count, 0);
    for (int r = 0; r < rows; ++r) {
      if (!is_attachment[r] || dependent[r] || pivot[r]) continue;
      watched[r] = 1;
      if (particle_of_row[r] >= 0) particle_watched[particle_of_row[r]] = 1;
    }
    for (int r = 0; r < rows; ++r) {
      if (is_attachment[r] && !dependent[r] && particle_of_row[r] >= 0 && particle_watched[particle_of_row[r]])
        watched[r] = 1;
    }
  }
  for (int r = 0; r < rows; ++r) {
    if (watched[r]) monitored_rows_.push_back(r);
  }
}

bool Dynamics::update_rank(double t, const Eigen::VectorXd& q) {
  if (dense_ || monitored_rows_.empty()) return false;
  // the watched rows' Jacobian (blocks with a watched row), rows numbered compactly
  auto index = [&](int row) {
    const auto it = std::lower_bound(monitored_rows_.begin(), monitored_rows_.end(), row);
    return it != monitored_rows_.end() && *it == row ? static_cast<int>(it - monitored_rows_.begin()) : -1;
  };
  all_.clear();
  for (const auto& block : model_.constraints) {
    const int first = block.first_row, count = block.constraint->rows();
    const auto it = std::lower_bound(monitored_rows_.begin(), monitored_rows_.end(), first);
    if (it == monitored_rows_.end() || *it >= first + count) continue;
    block.constraint->jacobian(q, t, first, all_);
  }
  // over the columns the watched rows touch only (a few), so the cost does not grow with the
  // particles the bodies hold
  Triplets entries;
  std::vector<int> columns;
  for (const auto& e : all_) {
    const int row = index(e.row());
    if (row < 0 || local_[e.col()] < 0) continue;
    columns.push_back(local_[e.col()]);
    entries.emplace_back(row, local_[e.col()], e.value());
  }
  std::sort(columns.begin(), columns.end());
  columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
  const int used = static_cast<int>(columns.size());
  RowAnalysisOptions options;
  options.eliminable.resize(used);
  monitor_weight_.resize(used);
  for (int k = 0; k < used; ++k) {
    options.eliminable[k] = particle_column_[columns[k]];
    monitor_weight_[k] = selection_c_[columns[k]];
  }
  for (auto& e : entries) {
    e = Eigen::Triplet<double>(e.row(), static_cast<int>(std::lower_bound(columns.begin(), columns.end(), e.col()) - columns.begin()), e.value());
  }
  Eigen::SparseMatrix<double> j(static_cast<int>(monitored_rows_.size()), used);
  j.setFromTriplets(entries.begin(), entries.end());
  // rank in the mass metric with the threshold of the small systems' solves
  options.column_weight = &monitor_weight_;
  options.relative_threshold = kRankThreshold;
  const RowDependence found = find_dependent_rows(j, options);
  const size_t watched_dropped = dropped_.size() - structural_dropped_.size();
  if (found.dependent.size() == watched_dropped) return false;
  // the rank changed: the rows dependent now, with the ones that always are
  std::vector<int> dropped = structural_dropped_;
  for (int k : found.dependent) dropped.push_back(monitored_rows_[k]);
  std::sort(dropped.begin(), dropped.end());
  select_rows(dropped);
  ++rank_changes_;
  return true;
}

void Dynamics::refuse_conflict(const std::vector<int>& rows) const {
  // the blocks of the rows, in order; refused only when an attachment takes part (a rigid
  // mechanism's dependency is a singular position, handled as the run goes)
  std::vector<size_t> blocks;
  for (int row : rows) {
    size_t k = 0;
    for (size_t b = 0; b < model_.constraints.size(); ++b) {
      if (model_.constraints[b].first_row <= row) k = b;
    }
    if (blocks.empty() || blocks.back() != k) {
      if (std::find(blocks.begin(), blocks.end(), k) == blocks.end()) blocks.push_back(k);
    }
  }
  std::sort(blocks.begin(), blocks.end());
  const ConstraintBlock* attachment = nullptr;
  std::string names;
  for (size_t k : blocks) {
    const ConstraintBlock& block = model_.constraints[k];
    if (block.origin == ConstraintBlock::Origin::kAttachment) attachment = &block;
    names += (names.empty() ? "'" : ", '") + block.constraint->name() + "'";
  }
  if (!attachment) return;
  throw InputError(attachment->where,
                   "the constraints " + names +
                       " contradict each other: attachments that hold particles in common tie their bodies "
                       "together, so these equations depend on each other, and the drivers or imposed motions "
                       "among them ask for different motions; hold each particle by one body, or drive the "
                       "bodies alike");
}

void Dynamics::assemble_jacobian(double t, const Eigen::VectorXd& q) {
  all_.clear();
  for (const auto& block : model_.constraints) block.constraint->jacobian(q, t, block.first_row, all_);
  local_j_.clear();
  prescribed_j_.clear();
  for (const auto& e : all_) {
    const int row = active_index_[e.row()];
    if (row < 0) continue;
    const int col = local_[e.col()];
    if (col >= 0) {
      local_j_.emplace_back(row, col, e.value());
    } else if (model_.is_prescribed[e.col()]) {
      prescribed_j_.emplace_back(row, e.col(), e.value());
    }
  }
}

void Dynamics::residual_all(double t, const Eigen::VectorXd& q) {
  phi_all_.resize(model_.constraint_rows);
  for (const auto& block : model_.constraints) block.constraint->residual(q, t, phi_all_.data() + block.first_row);
}

void Dynamics::time_derivative_all(double t, const Eigen::VectorXd& q) {
  phi_t_all_.resize(model_.constraint_rows);
  for (const auto& block : model_.constraints) {
    block.constraint->time_derivative(q, t, phi_t_all_.data() + block.first_row);
  }
}

void Dynamics::assemble_reduced(double t, const Eigen::VectorXd& q) {
  // active row -> reduced row, rebuilt from reduced_rows_ (cheap next to the triplets)
  std::vector<int>& row_of = active_index_work_;
  row_of.assign(active_.size(), -1);
  for (size_t r = 0; r < reduced_rows_.size(); ++r) row_of[reduced_rows_[r]] = static_cast<int>(r);
  all_.clear();
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    if (condensed_.block_condensed(k)) continue;
    const ConstraintBlock& block = model_.constraints[k];
    block.constraint->jacobian(q, t, block.first_row, all_);
  }
  reduced_j_.clear();
  prescribed_j_.clear();
  for (const auto& e : all_) {
    const int active = active_index_[e.row()];
    if (active < 0) continue;
    const int row = row_of[active];
    if (row < 0) continue;  // an eliminated particle's row of a joint kept in part
    const int col = reduced_col_[e.col()];
    if (col >= 0) {
      reduced_j_.emplace_back(row, col, e.value());
    } else if (model_.is_prescribed[e.col()]) {
      prescribed_j_.emplace_back(row, e.col(), e.value());
    }
  }
  condensed_.update(q);
}

void Dynamics::velocity_residual_all(const Eigen::VectorXd& qd) {
  nu_all_ = phi_t_all_;
  for (const auto& e : reduced_j_) nu_all_[active_[reduced_rows_[e.row()]]] += e.value() * qd[reduced_cols_[e.col()]];
  for (const auto& e : prescribed_j_) nu_all_[active_[reduced_rows_[e.row()]]] += e.value() * qd[e.col()];
  condensed_.velocity_residual(qd, nu_all_.data());
}

bool Dynamics::solve_dense(const Eigen::VectorXd& w, const double* a, const double* e,
                           DenseConstraintSolver& solver, Eigen::VectorXd& z) {
  // every row is active and reduced (no eliminated joints), so reduced row r is global row r
  const int nr = static_cast<int>(reduced_cols_.size()), mr = static_cast<int>(reduced_rows_.size());
  Eigen::MatrixXd& j = solver.jacobian();
  j.setZero();
  for (const auto& t : reduced_j_) j(t.row(), t.col()) += t.value();
  diag_.resize(nr);
  select_.resize(nr);
  rhs_.resize(nr + mr);
  for (int k = 0; k < nr; ++k) {
    diag_[k] = w[reduced_cols_[k]];
    select_[k] = selection_[reduced_cols_[k]];
    rhs_[k] = a ? a[reduced_cols_[k]] : 0.0;
  }
  for (int r = 0; r < mr; ++r) rhs_[nr + r] = e[active_[reduced_rows_[r]]];
  if (!solver.factorize(diag_.data(), select_.data(), kRankThreshold)) return false;
  x_.resize(nr + mr);
  solver.solve(rhs_.data(), rhs_.data() + nr, x_.data(), x_.data() + nr);
  if (!x_.allFinite()) return false;
  for (int k = 0; k < nr; ++k) z[reduced_cols_[k]] = x_[k];
  return true;
}

bool Dynamics::solve_constrained(const Eigen::VectorXd& w, const double* a, const double* e, KktSolver& solver,
                                 Eigen::VectorXd& z) {
  if (dense_) {
    return solve_dense(w, a, e, &solver == &kkt_ ? dense_acceleration_ : dense_projection_, z);
  }
  const int nr = static_cast<int>(reduced_cols_.size()), mr = static_cast<int>(reduced_rows_.size());
  diag_.resize(nr);
  rhs_.resize(nr + mr);
  for (int k = 0; k < nr; ++k) {
    diag_[k] = w[reduced_cols_[k]];
    rhs_[k] = a ? a[reduced_cols_[k]] : 0.0;
  }
  for (int r = 0; r < mr; ++r) rhs_[nr + r] = e[active_[reduced_rows_[r]]];
  coupling_.clear();
  if (!condensed_.empty()) {
    condensed_.add_body_blocks(w, reduced_col_, diag_, coupling_);
    condensed_.add_body_rhs(a, w, e, reduced_col_, rhs_);
  }
  if (nr > 0) {
    if (!solver.factorize(diag_, reduced_j_, mr, &coupling_)) return false;
    x_ = solver.solve(rhs_);
    if (!x_.allFinite()) return false;
    for (int k = 0; k < nr; ++k) z[reduced_cols_[k]] = x_[k];
  }
  condensed_.recover(e, z);
  return true;
}

std::vector<int> Dynamics::dependent_active_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) const {
  RowAnalysisOptions options;
  options.eliminable = particle_column_;
  options.relative_threshold = relative_threshold;
  return find_dependent_rows(j, options).dependent;
}

void Dynamics::throw_singular(double t, const Eigen::VectorXd& q, const std::string& during) {
  // find the blocks whose rows became dependent, to name them
  assemble_jacobian(t, q);
  Eigen::SparseMatrix<double> j(active_rows(), constrained_coordinates());
  j.setFromTriplets(local_j_.begin(), local_j_.end());
  std::string names;
  for (int a : dependent_active_rows(j, 1e-8)) {
    const std::string& name = block_of_row(active_[a]);
    if (names.find("'" + name + "'") == std::string::npos) names += (names.empty() ? "'" : ", '") + name + "'";
  }
  throw NumericalError({"constraint Jacobian", -1, t,
                        "the constraint Jacobian is singular during " + during +
                            (names.empty() ? std::string() : " (dependent: " + names + ")") +
                            "; the mechanism is at a toggle / locked position or a massless part is free",
                        "change the geometry or the driver so the mechanism avoids this position"});
}

void Dynamics::impose_prescribed(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const {
  for (const auto& p : model_.prescribed) {
    q[p.coordinate] = p.reference + p.displacement(t);
    qd[p.coordinate] = p.displacement.d1(t);
  }
}

void Dynamics::derivative(double t, const Eigen::VectorXd& q_in, const Eigen::VectorXd& qd_in, Eigen::VectorXd& qdd,
                          Eigen::Vector3d& power) {
  // imposed motions replace whatever the integrator carried for those coordinates
  const Eigen::VectorXd* qp = &q_in;
  const Eigen::VectorXd* qdp = &qd_in;
  if (!model_.prescribed.empty()) {
    q_work_ = q_in;
    qd_work_ = qd_in;
    impose_prescribed(t, q_work_, qd_work_);
    qp = &q_work_;
    qdp = &qd_work_;
  }
  const Eigen::VectorXd& q = *qp;
  const Eigen::VectorXd& qd = *qdp;
  const int n = model_.coordinate_count;

  // the parts' times come from one evaluation in kTimedEvery, counted that many times: reading
  // the clock four times would cost as much as the rest of a small system's evaluation
  const bool timed = evaluations_++ % kTimedEvery == 0;
  const auto now = [timed] { return timed ? Clock::now() : Clock::time_point{}; };

  // generalised forces: gravity, force elements, peridynamic bodies, the mouse
  auto start = now();
  // gravity, or zeros without it (a write, not a copy, of the whole vector)
  if (has_gravity_)
    g_ = model_.gravity_force;
  else
    g_.setZero(n);
  double dissipated = 0.0, external = 0.0, driver = 0.0;
  for (auto& f : model_.forces) {
    f->add_forces(q, qd, t, g_);
    dissipated += f->dissipation_power(q, qd);
    external += f->external_power(q, qd, t);
  }
  for (auto& flex : model_.flex_bodies) {
    flex->add_forces(q, qd, t, g_);
    if (flex->bond_damping() != 0.0 || flex->global_damping() != 0.0) dissipated += flex->dissipation_power(q, qd);
    external += flex->external_power(q, qd, t);
  }
  // contacts of [[contact]] (an empty list without them)
  for (auto& contact : model_.contacts) dissipated += contact->add_forces_dissipating(q, qd, t, g_);
  if (!held_.empty()) check_held_rotations(model_, held_, g_, t);
  if (mouse_) {
    const Vec2 target = mouse_->target_at(t);
    if (mouse_->point.body >= 0) {
      const Vec2 p = mouse_->point.position(q);
      const Vec2 v = mouse_->point.velocity(q, qd);
      const Vec2 force = mouse_->stiffness * (target - p) - mouse_->damping * v;
      mouse_->point.add_force(g_, force, 1.0, q);
      external += force.dot(v);
    }
    // a held patch of particles: each towards the target plus its offset
    for (size_t k = 0; k < mouse_->particle_coordinates.size(); ++k) {
      const int c = mouse_->particle_coordinates[k];
      const Vec2 p(q[c], q[c + 1]), v(qd[c], qd[c + 1]);
      const Vec2 force = mouse_->particle_stiffness[k] * (target + mouse_->offsets[k] - p) -
                         mouse_->particle_damping[k] * v;
      g_[c] += force.x();
      g_[c + 1] += force.y();
      external += force.dot(v);
    }
  }
  if (timed) force_seconds_ += kTimedEvery * since(start);

  // unconstrained coordinates: qdd = g / m (over every coordinate with mass, one vectorised pass;
  // the others are overwritten below); imposed ones: f''
  qdd.resize(n);
  qdd = g_.cwiseProduct(inverse_mass_);
  for (const auto& p : model_.prescribed) qdd[p.coordinate] = p.displacement.d2(t);

  // constrained coordinates: the augmented system, eliminated attachments condensed
  if (!constrained_.empty()) {
    start = now();
    const int m = active_rows();
    assemble_reduced(t, q);
    gamma_all_.resize(model_.constraint_rows);
    for (const auto& block : model_.constraints) {
      block.constraint->gamma(q, qd, t, gamma_all_.data() + block.first_row);
    }
    time_derivative_all(t, q);
    velocity_residual_all(qd);  // Phi_q qd + Phi_t
    e_all_ = gamma_all_;
    // imposed accelerations move to the right-hand side
    for (const auto& e : prescribed_j_) e_all_[active_[reduced_rows_[e.row()]]] -= e.value() * qdd[e.col()];
    // Baumgarte stabilisation: gamma - 2 alpha Phi_dot - beta^2 Phi
    if (correction_.method == CorrectionDef::Method::kBaumgarte && m > 0) {
      residual_all(t, q);
      const double a2 = 2.0 * correction_.alpha, b2 = correction_.beta * correction_.beta;
      for (int row : active_) e_all_[row] -= a2 * nu_all_[row] + b2 * phi_all_[row];
    }
    if (!solve_constrained(model_.mass, g_.data(), e_all_.data(), kkt_, qdd))
      throw_singular(t, q, "the acceleration solve");
    const int nr = reduced_coordinates();
    for (int r = 0; r < reduced_rows(); ++r) lambda_[reduced_rows_[r]] = x_[nr + r];
    // the rank as the run goes: count each change of the rows left out
    if (dense_ && dense_acceleration_.dependent() != last_dependent_) {
      last_dependent_ = dense_acceleration_.dependent();
      ++rank_changes_;
    }
    condensed_.multipliers(model_.mass, qdd, g_.data(), active_index_, lambda_);

    // drivers do work -lambda (Phi_q qd) on the system (power of the reaction -Phi_q^T lambda)
    for (int a = 0; a < m; ++a) {
      if (active_is_driver_[a]) driver -= lambda_[a] * (nu_all_[active_[a]] - phi_t_all_[active_[a]]);
    }
    // constraint forces on imposed coordinates are part of their reaction
    for (const auto& e : prescribed_j_) g_[e.col()] -= e.value() * lambda_[reduced_rows_[e.row()]];
    if (timed) constraint_seconds_ += kTimedEvery * since(start);
  }
  // imposed motions do the work of their reactions m qdd - g
  for (const auto& p : model_.prescribed) {
    const int c = p.coordinate;
    driver += (model_.mass[c] * qdd[c] - g_[c]) * qd[c];
  }
  power = Eigen::Vector3d(dissipated, external, driver);
}

double Dynamics::project_positions(double t, Eigen::VectorXd& q, double tolerance, int max_iterations) {
  if (active_.empty()) return 0.0;
  double error = position_violation(t, q);
  // Newton on min (dq^T W dq) subject to Phi(q + dq) = 0
  for (int it = 0; it < max_iterations && error > tolerance; ++it) {
    assemble_reduced(t, q);
    e_all_ = -phi_all_;
    dz_.setZero(model_.coordinate_count);
    if (!solve_constrained(weight_, nullptr, e_all_.data(), projection_kkt_, dz_))
      throw_singular(t, q, "the position projection");
    for (int c : constrained_) q[c] += dz_[c];
    error = position_violation(t, q);
    // with rank monitoring, converged once the rows this solve kept are satisfied (a row left
    // out depends on them to first order; its residual still shows in position_violation)
    if (dense_) error = selected_violation();
    if (!dense_ && !dropped_.empty()) {
      error = 0.0;
      for (int row : active_) error = std::max(error, std::abs(phi_all_[row]));
      if (!std::isfinite(error)) error = std::numeric_limits<double>::infinity();
    }
  }
  return error;
}

double Dynamics::project_positions_from(double t, const Eigen::VectorXd& q_start, Eigen::VectorXd& q,
                                        double tolerance, int max_iterations) {
  if (!dense_) return project_positions(t, q, tolerance, max_iterations);
  // the normals at the start, and the rows independent there (rank-revealing QR in the weights)
  const int nr = static_cast<int>(reduced_cols_.size());
  assemble_reduced(t, q_start);
  Eigen::MatrixXd& j = dense_projection_.jacobian();
  j.setZero();
  for (const auto& e : reduced_j_) j(e.row(), e.col()) += e.value();
  start_j_ = j;
  select_.resize(nr);
  diag_.resize(nr);
  for (int k = 0; k < nr; ++k) {
    select_[k] = selection_[reduced_cols_[k]];
    diag_[k] = weight_[reduced_cols_[k]];
  }
  if (!dense_projection_.factorize(diag_.data(), select_.data(), kRankThreshold))
    throw_singular(t, q_start, "the position projection");
  std::vector<int> rows;
  for (int r = 0; r < static_cast<int>(active_.size()); ++r) {
    if (!std::binary_search(dense_projection_.dependent().begin(), dense_projection_.dependent().end(), r))
      rows.push_back(r);
  }
  const int m = static_cast<int>(rows.size());
  residual_all(t, q);
  double error = selected_violation();
  for (int it = 0; it < max_iterations && error > tolerance; ++it) {
    // (J_k W^-1 J_0^T) dmu = -Phi, dq = W^-1 J_0^T dmu
    assemble_reduced(t, q);
    j.setZero();
    for (const auto& e : reduced_j_) j(e.row(), e.col()) += e.value();
    shake_matrix_.resize(m, m);
    shake_rhs_.resize(m);
    for (int a = 0; a < m; ++a) {
      shake_rhs_[a] = -phi_all_[rows[a]];
      for (int b = 0; b < m; ++b) {
        double v = 0.0;
        for (int k = 0; k < nr; ++k) v += j(rows[a], k) * start_j_(rows[b], k) / diag_[k];
        shake_matrix_(a, b) = v;
      }
    }
    shake_lu_.compute(shake_matrix_);
    const Eigen::VectorXd mu = shake_lu_.solve(shake_rhs_);
    if (!mu.allFinite()) throw_singular(t, q, "the position projection");
    for (int k = 0; k < nr; ++k) {
      double v = 0.0;
      for (int b = 0; b < m; ++b) v += start_j_(rows[b], k) * mu[b];
      q[reduced_cols_[k]] += v / diag_[k];
    }
    residual_all(t, q);
    error = selected_violation();
  }
  return error;
}

double Dynamics::selected_violation() const {
  const auto& left_out = dense_projection_.dependent();
  double worst = 0.0;
  for (int row = 0; row < model_.constraint_rows; ++row) {
    if (std::binary_search(left_out.begin(), left_out.end(), row)) continue;
    worst = std::max(worst, std::abs(phi_all_[row]));
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

double Dynamics::project_velocities(double t, const Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  if (active_.empty()) return 0.0;
  assemble_reduced(t, q);
  time_derivative_all(t, q);
  velocity_residual_all(qd);
  // the correction dqd solves [W J^T; J 0][dqd; mu] = [0; -(Phi_q qd + Phi_t)]
  e_all_ = -nu_all_;
  dz_.setZero(model_.coordinate_count);
  if (!solve_constrained(weight_, nullptr, e_all_.data(), projection_kkt_, dz_))
    throw_singular(t, q, "the velocity projection");
  double change = 0.0;
  for (int c : constrained_) {
    qd[c] += dz_[c];
    change = std::max(change, std::abs(dz_[c]));
  }
  return change;
}

double Dynamics::position_violation(double t, const Eigen::VectorXd& q) {
  if (active_.empty()) return 0.0;
  // every row, the ones dropped as dependent included: their violation is part of the figure
  residual_all(t, q);
  double worst = 0.0;
  for (int row = 0; row < model_.constraint_rows; ++row) worst = std::max(worst, std::abs(phi_all_[row]));
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

double Dynamics::velocity_violation(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (active_.empty()) return 0.0;
  assemble_reduced(t, q);
  time_derivative_all(t, q);
  velocity_residual_all(qd);
  double worst = 0.0;
  for (int row : active_) worst = std::max(worst, std::abs(nu_all_[row]));
  // the rows left out as dependent: Phi_q qd + Phi_t from their blocks' Jacobians
  if (!dense_ && !dropped_.empty()) {
    all_.clear();
    for (const auto& block : model_.constraints) {
      const int first = block.first_row, count = block.constraint->rows();
      const auto it = std::lower_bound(dropped_.begin(), dropped_.end(), first);
      if (it == dropped_.end() || *it >= first + count) continue;
      block.constraint->jacobian(q, t, first, all_);
    }
    Eigen::VectorXd& left_out = dz_;
    left_out = phi_t_all_;
    for (const auto& e : all_) left_out[e.row()] += e.value() * qd[e.col()];
    for (int row : dropped_) worst = std::max(worst, std::abs(left_out[row]));
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

std::vector<std::string> Dynamics::nearly_dependent_blocks(double t, const Eigen::VectorXd& q,
                                                          double relative_threshold) {
  std::vector<std::string> names;
  if (active_.empty()) return names;
  assemble_jacobian(t, q);
  Eigen::SparseMatrix<double> j(active_rows(), constrained_coordinates());
  j.setFromTriplets(local_j_.begin(), local_j_.end());
  for (int a : dependent_active_rows(j, relative_threshold)) {
    const std::string& name = block_of_row(active_[a]);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

std::string Dynamics::worst_constraint(double t, const Eigen::VectorXd& q) {
  if (active_.empty()) return "";
  residual_all(t, q);
  int worst_row = active_.front();
  for (int row : active_) {
    if (!(std::abs(phi_all_[row]) <= std::abs(phi_all_[worst_row]))) worst_row = row;
  }
  return block_of_row(worst_row);
}

}  // namespace periflex
