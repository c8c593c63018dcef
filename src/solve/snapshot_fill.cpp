// The snapshot for drawing and writers: the constant geometry built once, then poses, particles
// with their colour fields, markers, probes, active contacts, energies, the mouse's grip and the
// joints' reactions at the current state.
#include "solve/simulation_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel_chunks.h"

namespace periflex {

namespace {
// Bodies with fewer bonds than this send their bond pairs in snapshots.
constexpr long kDrawnBondLimit = 5000;

// Every flexible body's evaluations hold all intact bonds and leave no trace while it lives
// (PdBody::BreakTiming::kQuery); each body's own timing comes back at its end.
class QueryTimings {
 public:
  explicit QueryTimings(const SystemModel& model) : model_(model) {
    for (const auto& flex : model_.flex_bodies) {
      saved_.push_back(flex->break_timing());
      flex->set_break_timing(PdBody::BreakTiming::kQuery);
    }
  }
  ~QueryTimings() {
    for (size_t f = 0; f < saved_.size(); ++f) model_.flex_bodies[f]->set_break_timing(saved_[f]);
  }
  QueryTimings(const QueryTimings&) = delete;
  QueryTimings& operator=(const QueryTimings&) = delete;

 private:
  const SystemModel& model_;
  std::vector<PdBody::BreakTiming> saved_;
};

}  // namespace

void Simulation::fill_snapshot(Snapshot& out) const {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  const SystemModel& m = *s.model;
  const Eigen::VectorXd& q = s.state.q;
  const Eigen::VectorXd& qd = s.state.qd;

  // the constant part, built once
  if (!s.geometry) {
    auto g = std::make_shared<SceneGeometry>();
    g->scene_name = s.scene.name;
    SceneGeometry::Body ground;
    ground.name = "ground";
    ground.ground = true;
    g->bodies.push_back(ground);
    for (const auto& b : m.bodies) g->bodies.push_back({b.name, false, b.is_virtual, b.shapes});
    int first = 0;
    g->particle_attached.clear();
    for (const auto& flex : m.flex_bodies) {
      g->flex_bodies.push_back({flex->name(), first, flex->particle_count(), flex->grid_spacing()});
      first += flex->particle_count();
      const auto& ref = flex->reference_positions();
      for (int p = 0; p < flex->particle_count(); ++p) {
        g->reference_x.push_back(static_cast<float>(ref[2 * p]));
        g->reference_y.push_back(static_cast<float>(ref[2 * p + 1]));
        const BondStore& bonds = flex->bonds();
        g->bonds_initial.push_back(static_cast<uint16_t>(std::min<int64_t>(bonds.row[p + 1] - bonds.row[p], 65535)));
      }
      g->reference_xy.insert(g->reference_xy.end(), ref.begin(), ref.end());
      g->particle_volume.insert(g->particle_volume.end(), flex->volumes().begin(), flex->volumes().end());
    }
    g->particle_attached.assign(first, 0);
    g->particle_body.assign(first, 0);
    std::vector<int> coords;
    for (const auto& block : m.constraints) {
      if (block.origin != ConstraintBlock::Origin::kAttachment) continue;
      coords.clear();
      block.constraint->coordinates(coords);
      // the rigid body's coordinates come first (x, y, phi of rigid body c / 3: geometry index + 1)
      int holder = 0;
      for (int c : coords)
        if (c >= 0 && c < m.rigid_coordinates) holder = c / 3 + 1;
      for (int c : coords) {
        if (c < m.rigid_coordinates) continue;
        for (size_t f = 0; f < m.flex_bodies.size(); ++f) {
          const int off = m.flex_bodies[f]->coordinate_offset();
          if (c >= off && c < off + 2 * m.flex_bodies[f]->particle_count()) {
            g->particle_attached[g->flex_bodies[f].first_particle + (c - off) / 2] = 1;
            g->particle_body[g->flex_bodies[f].first_particle + (c - off) / 2] = holder;
          }
        }
      }
    }
    // bounds of the initial configuration
    Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
    auto grow = [&](const Vec2& p) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    };
    for (size_t k = 0; k < m.bodies.size(); ++k) grow(m.q0.segment<2>(3 * k));
    for (const auto& marker : m.markers) grow(marker.a.position(m.q0));
    for (int c = m.rigid_coordinates; c + 1 < m.coordinate_count; c += 2) grow(m.q0.segment<2>(c));
    if (lo.x() > hi.x()) lo = hi = Vec2::Zero();
    g->bounds_min = lo;
    g->bounds_max = hi;
    s.geometry = g;
  }
  out.geometry = s.geometry;
  out.time = s.time;
  out.step = s.steps;

  // rigid poses, ground first
  out.bodies.assign(1, Snapshot::Pose{});
  for (size_t k = 0; k < m.bodies.size(); ++k) {
    out.bodies.push_back({q[3 * k], q[3 * k + 1], q[3 * k + 2], qd[3 * k], qd[3 * k + 1], qd[3 * k + 2]});
  }
  fill_reactions(out);

  // particles
  out.px.clear();
  out.py.clear();
  out.damage.clear();
  out.displacement.clear();
  out.speed.clear();
  out.vx.clear();
  out.vy.clear();
  out.strain.clear();
  out.bonds_intact.clear();
  out.bond_pairs.clear();
  out.particle_q.clear();
  out.particle_qd.clear();
  std::vector<float> buffer;
  std::vector<std::pair<int, int>> pairs;
  out.max_damage = 0.0;
  int first = 0;
  for (const auto& flex : m.flex_bodies) {
    const int off = flex->coordinate_offset();
    const auto& ref = flex->reference_positions();
    for (int p = 0; p < flex->particle_count(); ++p) {
      const double x = q[off + 2 * p], y = q[off + 2 * p + 1];
      out.px.push_back(static_cast<float>(x));
      out.py.push_back(static_cast<float>(y));
      out.displacement.push_back(static_cast<float>(std::hypot(x - ref[2 * p], y - ref[2 * p + 1])));
      out.speed.push_back(static_cast<float>(std::hypot(qd[off + 2 * p], qd[off + 2 * p + 1])));
      out.vx.push_back(static_cast<float>(qd[off + 2 * p]));
      out.vy.push_back(static_cast<float>(qd[off + 2 * p + 1]));
    }
    if (out.full_precision) {
      out.particle_q.insert(out.particle_q.end(), q.data() + off, q.data() + off + 2 * flex->particle_count());
      out.particle_qd.insert(out.particle_qd.end(), qd.data() + off, qd.data() + off + 2 * flex->particle_count());
    }
    flex->damage(buffer);
    for (float d : buffer) out.max_damage = std::max(out.max_damage, static_cast<double>(d));
    out.damage.insert(out.damage.end(), buffer.begin(), buffer.end());
    flex->max_stretch(q, buffer);
    out.strain.insert(out.strain.end(), buffer.begin(), buffer.end());
    // intact bonds of each particle, for the window's inspector
    const BondStore& bonds = flex->bonds();
    const std::vector<uint8_t>& broken = flex->bond_state().broken;
    const size_t at = out.bonds_intact.size();
    const int n = flex->particle_count();
    out.bonds_intact.resize(at + n);
    uint16_t* intact = out.bonds_intact.data() + at;
    parallel_chunks(n, [&](int64_t, int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        int64_t count = 0;
        for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) count += broken[k] ? 0 : 1;
        intact[i] = static_cast<uint16_t>(std::min<int64_t>(count, 65535));
      }
    });
    if (flex->bond_count() < kDrawnBondLimit) {
      flex->bond_pairs(pairs, kDrawnBondLimit);
      for (const auto& [i, j] : pairs) out.bond_pairs.emplace_back(first + i, first + j);
    }
    first += flex->particle_count();
  }

  // joints, drivers, attachments, springs, probes
  out.markers.clear();
  for (const auto& marker : m.markers)
    out.markers.push_back({marker.kind, marker.a.position(q), marker.b.position(q), marker.a.body + 1, marker.b.body + 1});
  out.springs.clear();
  for (const auto& line : m.spring_lines) out.springs.push_back({line.a.position(q), line.b.position(q)});
  out.probes.clear();
  for (const auto& p : m.probes) {
    const Vec2 at = p.is_particle() ? Vec2(q[p.particle_coordinate], q[p.particle_coordinate + 1]) : p.point.position(q);
    out.probes.push_back({p.name, at, p.particle, p.is_particle() ? 0 : p.point.body + 1});
  }
  // active contacts (a pass of each contact of its own; nothing without [[contact]])
  s.contact_points.clear();
  for (const auto& contact : m.contacts) contact->collect_points(q, qd, s.contact_points);
  out.contacts.clear();
  for (const ContactPoint& c : s.contact_points) out.contacts.push_back({c.point, c.force});
  out.energies = s.energies();
  out.violation_position = s.dynamics->position_violation(s.time, q);
  out.violation_velocity = s.dynamics->velocity_violation(s.time, q, qd);
  out.broken_bonds = s.broken_bonds;
  // what the mouse holds: the anchor, the pull and its limits
  out.mouse = Snapshot::MouseGrip{};
  if (const auto& mouse = s.dynamics->mouse_spring()) {
    out.mouse.held = true;
    out.mouse.anchor = mouse->target_at(s.time);
    out.mouse.target = mouse->target;
    out.mouse.force = grip_force(*mouse, s.time, q);
    out.mouse.max_speed = mouse->speed;
    out.mouse.max_force = mouse->point.body >= 0 ? 0.0 : s.grip.max_force;
  }
}

void Simulation::fill_reactions(Snapshot& out) const {
  const TeamSizeScope team(impl_->scene.solver.threads);
  Impl& s = *impl_;
  out.reactions.clear();
  if (!out.with_reactions || !s.dynamics->has_constraints()) return;
  // the multipliers at this very state (not at a trial stage of the last step), from an
  // evaluation that leaves the run as it was: the flexible bodies hold every intact bond for it
  // (a bond the next step's evaluation breaks would otherwise break here, and that row's forces
  // be summed another way there)
  const QueryTimings query(*s.model);
  Eigen::VectorXd qdd;
  Eigen::Vector3d power;
  try {
    s.dynamics->derivative(s.time, s.state.q, s.state.qd, qdd, power);
  } catch (const NumericalError&) {
    return;
  }
  // each block's rows of -Phi_q^T lambda on the rigid coordinates it touches
  const int rigid = s.model->rigid_coordinates;
  Triplets jacobian;
  for (const auto& block : s.model->constraints) {
    if (block.origin == ConstraintBlock::Origin::kAttachment) continue;
    jacobian.clear();
    block.constraint->jacobian(s.state.q, s.time, 0, jacobian);
    const size_t first = out.reactions.size();
    for (const auto& e : jacobian) {
      if (e.col() >= rigid) continue;
      const int body = e.col() / 3 + 1;
      auto it = std::find_if(out.reactions.begin() + static_cast<std::ptrdiff_t>(first), out.reactions.end(),
                             [body](const Snapshot::Reaction& r) { return r.body == body; });
      if (it == out.reactions.end()) {
        out.reactions.push_back({block.constraint->name(), body, 0.0, 0.0, 0.0});
        it = out.reactions.end() - 1;
      }
      const double f = -e.value() * s.dynamics->row_multiplier(block.first_row + e.row());
      (e.col() % 3 == 0 ? it->fx : e.col() % 3 == 1 ? it->fy : it->moment) += f;
    }
  }
}

}  // namespace periflex
