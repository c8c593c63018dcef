// The structure of d qdd / d(q, qd) taken from the model, for the implicit integrators: found
// in time linear in the coordinates and bonds, where perturbing every coordinate once costs a
// force evaluation per coordinate (the square of the model's size).
//
// What derivative() computes, row by row, and what each row therefore reads:
//  - a free coordinate: qdd = g / m, so the columns its forces couple (force elements, bonds,
//    contacts, the mouse spring);
//  - an imposed or held coordinate: a function of time (the diagonal only); the columns of
//    imposed coordinates change nothing, as derivative() overwrites them;
//  - a constrained coordinate: the solve of [W Phi_q^T; Phi_q 0][z; lambda] = [g; gamma], which
//    couples every coordinate of a connected group of constraints (a component). When the
//    equations that stay in the matrix are as many as its unknowns there, the motion of the
//    component is determined by the constraints alone (z = Phi_q^-1 gamma: grips turned by
//    drivers), and its rows read only the coordinates of those equations; an eliminated
//    particle (condensed_attachments.h) reads them, its own coordinates and its body's. Else
//    the forces enter, and every row of the component reads every column of its equations
//    and of the forces on any of its coordinates.
#include <algorithm>
#include <numeric>

#include "solve/dynamics.h"

namespace periflex {

namespace {

// Union-find with path halving over the constrained coordinates.
int find_root(std::vector<int>& parent, int k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

}  // namespace

bool Dynamics::jacobian_pattern(double t, const Eigen::VectorXd& q, SparsityPattern& pattern) {
  const int n = model_.coordinate_count;
  pattern.reset(n);

  // the forces' couplings, by column
  SparsityPattern& forces = force_pattern_;
  forces.reset(n);
  for (const auto& f : model_.forces)
    if (!f->add_coupling(q, forces)) return false;
  for (const auto& flex : model_.flex_bodies)
    if (!flex->add_coupling(q, forces)) return false;
  for (const auto& contact : model_.contacts)
    if (!contact->add_coupling(q, forces)) return false;
  if (mouse_) {
    if (mouse_->point.body >= 0) forces.add_block(mouse_->point.coordinates(), mouse_->point.coordinates());
    for (int c : mouse_->particle_coordinates) forces.add_block({c, c + 1}, {c, c + 1});
  }
  forces.finish();

  // components: constrained coordinates joined by the blocks they appear in together
  const int nc = static_cast<int>(constrained_.size());
  std::vector<int> parent(nc);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> coords;
  std::vector<int> block_root(model_.constraints.size(), -1);
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    coords.clear();
    model_.constraints[k].constraint->coordinates(coords);
    for (int c : coords) {
      if (local_[c] < 0) continue;
      const int root = find_root(parent, local_[c]);
      if (block_root[k] < 0)
        block_root[k] = root;
      else
        parent[root] = find_root(parent, block_root[k]);
    }
  }
  std::vector<int> component(n, -1);  // by global coordinate; -1: not constrained
  std::vector<int> id(nc, -1);
  int components = 0;
  for (int k = 0; k < nc; ++k) {
    const int root = find_root(parent, k);
    if (id[root] < 0) id[root] = components++;
    component[constrained_[k]] = id[root];
  }
  std::vector<std::vector<int>> members(components);
  for (int c : constrained_) members[component[c]].push_back(c);

  // determined components: as many equations stay in the matrix as unknowns (the small dense
  // systems find their rank at every solve, so they are never counted as determined)
  std::vector<int> unknowns(components, 0), equations(components, 0);
  for (int c : reduced_cols_) ++unknowns[component[c]];
  // the columns the equations in the matrix read (Jacobian entries of their rows; gamma and
  // the Baumgarte terms read the same), per component, and those of all its equations
  std::vector<std::vector<int>> kept_columns(components), all_columns(components);
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    if (block_root[k] < 0) continue;
    const int group = component[constrained_[block_root[k]]];
    const ConstraintBlock& block = model_.constraints[k];
    all_.clear();
    block.constraint->jacobian(q, t, block.first_row, all_);
    for (const auto& e : all_) {
      if (local_[e.col()] < 0) continue;
      all_columns[group].push_back(e.col());
      const int row = e.row();
      if (active_index_[row] >= 0 && !condensed_.row_condensed(row)) kept_columns[group].push_back(e.col());
    }
    for (int r = 0; r < block.constraint->rows(); ++r) {
      const int row = block.first_row + r;
      if (active_index_[row] >= 0 && !condensed_.row_condensed(row)) ++equations[group];
    }
  }
  auto unique_sorted = [](std::vector<int>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  std::vector<char> determined(components, 0);
  for (int g = 0; g < components; ++g) {
    determined[g] = !dense_ && equations[g] == unknowns[g];
    unique_sorted(kept_columns[g]);
    unique_sorted(all_columns[g]);
  }

  // determined: the unknowns in the matrix read the kept equations' columns; an eliminated
  // particle reads them too, its own coordinates and those of its joint's body
  for (int g = 0; g < components; ++g) {
    if (!determined[g]) continue;
    for (int c : members[g]) {
      if (!condensed_.coordinate_condensed(c)) {
        for (int col : kept_columns[g]) pattern.add(c, col);
      }
    }
  }
  for (size_t k = 0; k < model_.constraints.size(); ++k) {
    if (block_root[k] < 0 || !determined[component[constrained_[block_root[k]]]]) continue;
    coords.clear();
    model_.constraints[k].constraint->coordinates(coords);
    std::vector<int> body, particles;
    for (int c : coords) {
      if (local_[c] < 0) continue;
      if (c < model_.rigid_coordinates)
        body.push_back(c);
      else if (condensed_.coordinate_condensed(c))
        particles.push_back(c);
    }
    const int group = component[constrained_[block_root[k]]];
    for (int p : particles) {
      for (int col : kept_columns[group]) pattern.add(p, col);
      for (int col : body) pattern.add(p, col);
      const int x = p - (p - model_.rigid_coordinates) % 2;  // the particle's x (slices start even)
      pattern.add(p, x);
      pattern.add(p, x + 1);
    }
  }

  // not determined: every row of the component reads every column of its equations
  for (int g = 0; g < components; ++g) {
    if (!determined[g]) pattern.add_block(members[g], all_columns[g]);
  }

  // the forces: a free row reads the columns of its forces; a component that is not determined
  // reads, in every row, the columns of the forces on any of its coordinates (once per column)
  std::vector<int> stamp(components, -1);
  const std::vector<int>& start = forces.start();
  const std::vector<int>& rows = forces.rows();
  for (int col = 0; col < n; ++col) {
    for (int k = start[col]; k < start[col + 1]; ++k) {
      const int row = rows[k];
      const int g = component[row];
      if (g < 0) {
        if (!model_.is_prescribed[row]) pattern.add(row, col);
      } else if (!determined[g] && stamp[g] != col) {
        stamp[g] = col;
        for (int member : members[g]) pattern.add(member, col);
      }
    }
  }
  pattern.finish();
  return true;
}

// A free row is g / m (the first case above): scaled by m it is a row of the forces' Jacobian.
void Dynamics::free_masses(Eigen::VectorXd& mass) {
  const int n = model_.coordinate_count;
  mass.setZero(n);
  for (int c = 0; c < n; ++c)
    if (local_[c] < 0 && !model_.is_prescribed[c] && model_.mass[c] > 0.0) mass[c] = model_.mass[c];
}

}  // namespace periflex
