// The constraint rows of Dynamics: which rows stay in the solve (dependent ones left out, at
// the start and whenever the rank changes), the rows the large systems' rank monitor watches,
// the rank saved with the state, and the names of blocks for diagnostics.
#include "solve/dynamics.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "solve/held_rotations.h"
#include "solve/redundancy.h"

namespace periflex {

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

std::vector<int> Dynamics::dependent_active_rows(const Eigen::SparseMatrix<double>& j, double relative_threshold) const {
  RowAnalysisOptions options;
  options.eliminable = particle_column_;
  options.relative_threshold = relative_threshold;
  return find_dependent_rows(j, options).dependent;
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
