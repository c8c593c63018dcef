// PdBody: the facade the solver sees, and the force evaluation every material law runs through
// (its law's bond forces, then global damping and loads). Building is in pd_body_build.cpp,
// breaking bonds and the state in pd_fracture.cpp, per-particle fields in pd_body_fields.cpp.
#include "pd/pd_body.h"

#include <vector>

#include "pd/pd_body_impl.h"

namespace periflex {

PdBody::PdBody(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PdBody::~PdBody() = default;

const std::string& PdBody::name() const { return impl_->def.name; }
int PdBody::particle_count() const { return impl_->n(); }
int PdBody::coordinate_offset() const { return impl_->offset; }
const std::vector<double>& PdBody::reference_positions() const { return impl_->reference; }
const std::vector<double>& PdBody::masses() const { return impl_->mass; }
const std::vector<double>& PdBody::volumes() const { return impl_->volume; }
double PdBody::grid_spacing() const { return impl_->dx; }
double PdBody::horizon() const { return impl_->delta; }
long PdBody::bond_count() const { return static_cast<long>(impl_->bonds.directed_count() / 2); }
long PdBody::broken_bond_count() const { return impl_->broken_pairs; }
bool PdBody::fracture_enabled() const { return impl_->fracture; }
void PdBody::set_bond_damping(double value) { impl_->bond_damping = value; }
void PdBody::set_global_damping(double value) { impl_->global_damping = value; }
void PdBody::set_break_timing(BreakTiming timing) { impl_->break_timing = timing; }
PdBody::BreakTiming PdBody::break_timing() const { return impl_->break_timing; }
void PdBody::set_step_end(double t_end, double half_kick) {
  impl_->step_end = t_end;
  impl_->half_kick = half_kick;
}

void PdBody::set_fracture_enabled(bool enabled) {
  impl_->fracture = enabled;
  impl_->stretch_cache_valid = false;
}
double PdBody::bond_damping() const { return impl_->bond_damping; }
double PdBody::global_damping() const { return impl_->global_damping; }
const std::vector<std::string>& PdBody::warnings() const { return impl_->warnings; }
double PdBody::micromodulus() const { return impl_->c; }
double PdBody::critical_stretch() const { return impl_->s0; }
const BondStore& PdBody::bonds() const { return impl_->bonds; }
const BondState& PdBody::bond_state() const { return impl_->live; }
std::vector<PrescribedCoordinate> PdBody::prescribed_coordinates() const { return impl_->prescribed; }

std::vector<double> PdBody::initial_velocities() const {
  const Impl& m = *impl_;
  std::vector<double> v(2 * m.n());
  for (int i = 0; i < m.n(); ++i) {
    v[2 * i] = m.def.velocity.x();
    v[2 * i + 1] = m.def.velocity.y();
  }
  // imposed coordinates start with their imposed rate
  for (const PrescribedCoordinate& pc : m.prescribed) v[pc.coordinate - m.offset] = pc.displacement.d1(0.0);
  return v;
}

double PdBody::critical_time_step() const { return impl_->law->critical_time_step(impl_->bonds, impl_->live,
                                  impl_->mass); }

void PdBody::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) {
  Impl& m = *impl_;
  LawEvaluation e;
  e.pos = m.pos(q);
  e.vel = qd.data() + m.offset;
  e.eta_over_e = m.bond_damping / m.def.material.youngs_modulus;
  e.force = g.data() + m.offset;

  // with fracture on the force loop also sees the stretch: an evaluation that breaks bonds leaves
  // out those past s0; one that holds every bond leaves the row maxima for update_fracture and
  // copies the positions it saw, chunk by chunk, so update_fracture knows they are its own.
  if (m.device) {
    add_device_bond_forces(m, e, t);
  } else if (m.breaks_in_evaluation()) {
    m.stretch_cache_valid = false;
    double energy = 0.0;
    const double half_kick = t == m.step_end ? m.half_kick : 0.0;
    const long broken = m.law->add_forces_breaking(m.bonds, m.live, e, m.no_fail_flags(), m.row_broke, half_kick,
                                                   energy);
    m.pending_broken += broken;
    m.pending_energy += energy;
    m.broken_pairs += broken;
  } else if (m.tracks_stretch() && m.break_timing != BreakTiming::kQuery) {
    // bonds break after the step (update_fracture), from these row maxima
    m.stretch_cache_pos.resize(2 * m.n());
    m.stretch_cache_most.resize(m.n());
    m.stretch_cache_valid = true;
    e.row_max = m.stretch_cache_most.data();
    e.pos_copy = m.stretch_cache_pos.data();
    m.law->add_forces(m.bonds, m.live, e);
  } else {
    m.law->add_forces(m.bonds, m.live, e);
  }

  // mass-proportional damping -alpha m v
  double* force = e.force;
  const double* vel = e.vel;
  if (m.global_damping > 0.0) {
    for (int i = 0; i < m.n(); ++i) {
      force[2 * i] -= m.global_damping * m.mass[i] * vel[2 * i];
      force[2 * i + 1] -= m.global_damping * m.mass[i] * vel[2 * i + 1];
    }
  }

  // tractions and body forces
  for (const AppliedLoad& load : m.loads) {
    const double fx = load.fx ? load.scale * (*load.fx)(t) : 0.0;
    const double fy = load.fy ? load.scale * (*load.fy)(t) : 0.0;
    for (size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      const double w = load.weights.empty() ? 1.0 : load.weights[k];
      force[2 * i] += w * fx;
      force[2 * i + 1] += w * fy;
    }
  }
}

bool PdBody::add_coupling(const Eigen::VectorXd&, SparsityPattern& pattern) const {
  const Impl& m = *impl_;
  const BondStore& bonds = m.bonds;
  // both coordinates of particle i against both of particle j
  auto couple = [&](int i, int j) {
    const int r = m.offset + 2 * i, c = m.offset + 2 * j;
    pattern.add(r, c);
    pattern.add(r, c + 1);
    pattern.add(r + 1, c);
    pattern.add(r + 1, c + 1);
  };
  if (!m.law->reaches_second_neighbours()) {
    for (int i = 0; i < m.n(); ++i) {
      couple(i, i);
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
        if (!m.live.broken[b]) couple(i, bonds.neighbor[b]);
    }
    return true;
  }
  // the particles within two intact bonds, each once per row (a stamp per particle)
  std::vector<int> seen(m.n(), -1);
  for (int i = 0; i < m.n(); ++i) {
    auto reach = [&](int j) {
      if (seen[j] == i) return;
      seen[j] = i;
      couple(i, j);
    };
    reach(i);
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (m.live.broken[b]) continue;
      const int j = bonds.neighbor[b];
      reach(j);
      for (int64_t d = bonds.row[j]; d < bonds.row[j + 1]; ++d)
        if (!m.live.broken[d]) reach(bonds.neighbor[d]);
    }
  }
  return true;
}

double PdBody::potential_energy(const Eigen::VectorXd& q) const {
  return impl_->law->strain_energy(impl_->bonds, impl_->live, impl_->pos(q));
}

double PdBody::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  const Impl& m = *impl_;
  const double* vel = qd.data() + m.offset;
  double power = 0.0;
  const double eta_over_e = m.bond_damping / m.def.material.youngs_modulus;
  if (eta_over_e > 0.0) power += m.law->damping_power(m.bonds, m.live, m.pos(q), vel, eta_over_e);
  if (m.global_damping > 0.0) {
    for (int i = 0; i < m.n(); ++i)
      power += m.global_damping * m.mass[i] * (vel[2 * i] * vel[2 * i] + vel[2 * i + 1] * vel[2 * i + 1]);
  }
  return power;
}

double PdBody::external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const {
  const Impl& m = *impl_;
  (void)q;
  const double* vel = qd.data() + m.offset;
  double power = 0.0;
  for (const AppliedLoad& load : m.loads) {
    const double fx = load.fx ? load.scale * (*load.fx)(t) : 0.0;
    const double fy = load.fy ? load.scale * (*load.fy)(t) : 0.0;
    for (size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      const double w = load.weights.empty() ? 1.0 : load.weights[k];
      power += w * (fx * vel[2 * i] + fy * vel[2 * i + 1]);
    }
  }
  return power;
}

}  // namespace periflex
