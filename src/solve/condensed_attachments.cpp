#include "solve/condensed_attachments.h"

#include <cmath>

namespace periflex {

void CondensedAttachments::build(const SystemModel& model, const std::vector<int>& active_index, bool enabled) {
  particles_.clear();
  block_condensed_.assign(model.constraints.size(), 0);
  slaved_.assign(model.coordinate_count, 0);
  row_condensed_.assign(model.constraint_rows, 0);
  if (!enabled) return;

  // how many blocks reach each coordinate through rows that stay (a particle whose rows in a
  // joint were all left out as dependent is not reached by that joint)
  std::vector<int> blocks_on(model.coordinate_count, 0), coords;
  for (const Attachment& attachment : model.attachments) {
    const RigidFlexibleJoint& joint = *attachment.joint;
    const int body = joint.body();
    for (int p = 0; p < joint.particle_count(); ++p) {
      const int row = attachment.first_row + 2 * p;
      if (active_index[row] < 0 && active_index[row + 1] < 0) continue;
      const int c = joint.particle_coordinates()[p];
      ++blocks_on[c];
      ++blocks_on[c + 1];
    }
    if (body >= 0)
      for (int axis = 0; axis < 3; ++axis) ++blocks_on[3 * body + axis];
  }
  for (const auto& block : model.constraints) {
    if (block.origin == ConstraintBlock::Origin::kAttachment) continue;  // counted above
    coords.clear();
    block.constraint->coordinates(coords);
    std::vector<int> seen;
    for (int c : coords) {
      bool repeat = false;
      for (int s : seen) repeat = repeat || s == c;
      if (repeat) continue;
      seen.push_back(c);
      ++blocks_on[c];
    }
  }

  // particle by particle: one whose rows stay and that no other staying row reaches
  for (const Attachment& attachment : model.attachments) {
    const RigidFlexibleJoint& joint = *attachment.joint;
    int condensed = 0;
    for (int p = 0; p < joint.particle_count(); ++p) {
      const int c = joint.particle_coordinates()[p];
      const int row = attachment.first_row + 2 * p;
      bool eligible = active_index[row] >= 0 && active_index[row + 1] >= 0;
      for (int axis = 0; axis < 2 && eligible; ++axis) {
        eligible = blocks_on[c + axis] == 1 && !model.is_prescribed[c + axis];
      }
      if (!eligible) continue;
      const Vec2 s = joint.local_position(p);
      particles_.push_back({c, joint.body(), row, s.x(), s.y()});
      slaved_[c] = slaved_[c + 1] = 1;
      row_condensed_[row] = row_condensed_[row + 1] = 1;
      ++condensed;
    }
    block_condensed_[attachment.block] = condensed == joint.particle_count();
  }
}

void CondensedAttachments::update(const Eigen::VectorXd& q) {
  int body = -2;
  double c = 1.0, s = 0.0;
  for (Particle& p : particles_) {
    if (p.body != body) {
      body = p.body;
      const double phi = body >= 0 ? q[3 * body + 2] : 0.0;
      c = std::cos(phi);
      s = std::sin(phi);
    }
    p.world_x = c * p.local_x - s * p.local_y;
    p.world_y = s * p.local_x + c * p.local_y;
  }
}

void CondensedAttachments::add_body_blocks(const Eigen::VectorXd& w, const std::vector<int>& reduced,
                                           Eigen::VectorXd& diag, Triplets& coupling) const {
  // per body: sum w_p [1 0 -Sy; 0 1 Sx; -Sy Sx Sx^2+Sy^2], S = A s'_p; the particles of one
  // joint are contiguous, so the sums run per run of the same body
  size_t k = 0;
  while (k < particles_.size()) {
    const int body = particles_[k].body;
    double m = 0.0, mx = 0.0, my = 0.0, inertia = 0.0;
    for (; k < particles_.size() && particles_[k].body == body; ++k) {
      const Particle& p = particles_[k];
      const double wp = w[p.coordinate];
      m += wp;
      mx += wp * p.world_x;
      my += wp * p.world_y;
      inertia += wp * (p.world_x * p.world_x + p.world_y * p.world_y);
    }
    if (body < 0) continue;
    const int x = reduced[3 * body], y = reduced[3 * body + 1], phi = reduced[3 * body + 2];
    diag[x] += m;
    diag[y] += m;
    diag[phi] += inertia;
    coupling.emplace_back(x, phi, -my);
    coupling.emplace_back(phi, x, -my);
    coupling.emplace_back(y, phi, mx);
    coupling.emplace_back(phi, y, mx);
  }
}

void CondensedAttachments::add_body_rhs(const double* a, const Eigen::VectorXd& w, const double* e,
                                        const std::vector<int>& reduced, Eigen::VectorXd& rhs) const {
  for (const Particle& p : particles_) {
    if (p.body < 0) continue;
    const double wp = w[p.coordinate];
    const double tx = (a ? a[p.coordinate] : 0.0) + wp * e[p.row];
    const double ty = (a ? a[p.coordinate + 1] : 0.0) + wp * e[p.row + 1];
    rhs[reduced[3 * p.body]] += tx;
    rhs[reduced[3 * p.body + 1]] += ty;
    rhs[reduced[3 * p.body + 2]] += -p.world_y * tx + p.world_x * ty;
  }
}

void CondensedAttachments::recover(const double* e, Eigen::VectorXd& z) const {
  for (const Particle& p : particles_) {
    double zx = -e[p.row], zy = -e[p.row + 1];
    if (p.body >= 0) {
      const double w = z[3 * p.body + 2];
      zx += z[3 * p.body] - p.world_y * w;
      zy += z[3 * p.body + 1] + p.world_x * w;
    }
    z[p.coordinate] = zx;
    z[p.coordinate + 1] = zy;
  }
}

void CondensedAttachments::velocity_residual(const Eigen::VectorXd& qd, double* out) const {
  // Phi_q qd = B_p qd_v - xd_p (no explicit time dependence)
  for (const Particle& p : particles_) {
    double vx = 0.0, vy = 0.0;
    if (p.body >= 0) {
      const double w = qd[3 * p.body + 2];
      vx = qd[3 * p.body] - p.world_y * w;
      vy = qd[3 * p.body + 1] + p.world_x * w;
    }
    out[p.row] = vx - qd[p.coordinate];
    out[p.row + 1] = vy - qd[p.coordinate + 1];
  }
}

void CondensedAttachments::multipliers(const Eigen::VectorXd& w, const Eigen::VectorXd& z, const double* a,
                                       const std::vector<int>& active_index, Eigen::VectorXd& lambda) const {
  for (const Particle& p : particles_) {
    for (int axis = 0; axis < 2; ++axis) {
      const int c = p.coordinate + axis;
      lambda[active_index[p.row + axis]] = w[c] * z[c] - (a ? a[c] : 0.0);
    }
  }
}

}  // namespace periflex
