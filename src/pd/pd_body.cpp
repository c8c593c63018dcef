#include "pd/pd_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "pd/bond_kernel.h"
#include "pd/neighbor_search.h"
#include "pd/particle_grid.h"
#include "pd/pd_material.h"
#include "pd/state_based_kernel.h"
#include "pd/state_based_material.h"
#include "pd/state_based_surface.h"

namespace periflex {

namespace {

// Largest grid a body may request; above it set-up refuses before allocating anything.
constexpr double kMaxParticles = 2e7;

// A traction or body force: force on each listed particle = scale * (fx(t), fy(t)).
struct AppliedLoad {
  std::vector<int> particles;
  double scale = 0.0;
  std::optional<TimeFunction> fx, fy;
};

// True when the bond [a, b] crosses the notch [c, d]. The notch is a closed segment: a bond that
// passes exactly through one of its end points is cut, as it would be by a notch reaching a
// hair further. The bond's own ends must lie strictly on either side of the notch's line: a bond
// from a particle sitting on the notch line is not cut (it only touches). Within `tolerance`
// (an area: a billionth of a grid cell) a signed area counts as zero.
bool notch_cuts_bond(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tolerance) {
  const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);  // bond ends against the notch line
  const bool ends_apart = (o3 > tolerance && o4 < -tolerance) || (o3 < -tolerance && o4 > tolerance);
  if (!ends_apart) return false;
  const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);  // notch ends against the bond line
  return std::min(o1, o2) <= tolerance && std::max(o1, o2) >= -tolerance;
}

SourceLocation with_key(SourceLocation where, const std::string& key) {
  where.key = where.key.empty() ? key : where.key + "." + key;
  return where;
}

}  // namespace

struct PdBody::Impl {
  FlexBodyDef def;
  int offset = 0;
  ParticleGrid grid;
  std::vector<double> reference, mass, volume;
  BondStore bonds;
  std::vector<uint8_t> no_fail;          // 1: bonds at this particle never break
  std::vector<double> initial_weight;    // sum of partial-volume factors of the initial bonds
  std::vector<double> class_weight;      // partial-volume factor per bond length class
  double dx = 0.0, delta = 0.0, c = 0.0, s0 = 0.0;
  bool fracture = false;
  double bond_damping = 0.0, global_damping = 0.0;
  long broken_pairs = 0;
  // model = "state_based": the LPS constants and per-particle state; bonds.stiffness then holds
  // each bond's weight w beta instead of its stiffness (state_based_kernel.h)
  bool state_based = false;
  StateBasedModel lps;
  std::vector<PrescribedCoordinate> prescribed;
  std::vector<AppliedLoad> loads;
  std::vector<std::string> warnings;

  // the row maxima of the stretch, found by the last force evaluation, and the positions they
  // belong to: update_fracture at the same positions (the usual case) skips its own pass
  std::vector<double> stretch_cache_pos, stretch_cache_most;
  bool stretch_cache_valid = false;
  bool tracks_stretch() const { return fracture && std::isfinite(s0); }
  PdBody::BreakTiming break_timing = PdBody::BreakTiming::kInEvaluation;
  double step_end = std::numeric_limits<double>::quiet_NaN(), half_kick = 0.0;
  std::vector<uint8_t> row_broke;   // per particle: a bond of the row broke in this evaluation
  long pending_broken = 0;          // broken by force evaluations since update_fracture
  double pending_energy = 0.0;

  // Partial-volume factor of the neighbour at grid offset (a, b): without the correction 1
  // inside the horizon; with it the exact fraction of its cell inside the horizon disc
  // (cells whose centre lies beyond delta + dx/2 hold under 1% and are left out).
  int table_size = 0;
  std::vector<double> beta_table;  // by (|a|, |b|)
  void build_beta_table() {
    const double ratio = def.horizon_ratio;
    table_size = static_cast<int>(std::ceil(ratio + 0.5)) + 1;
    beta_table.assign(table_size * table_size, 0.0);
    for (int a = 0; a < table_size; ++a) {
      for (int b = 0; b < table_size; ++b) {
        const double r2 = double(a) * a + double(b) * b;
        if (!def.partial_volume_correction)
          beta_table[a * table_size + b] = r2 <= ratio * ratio * (1 + 1e-12) ? 1.0 : 0.0;
        else if (r2 < (ratio + 0.5) * (ratio + 0.5) * (1 - 1e-12))
          beta_table[a * table_size + b] = cell_fraction_in_disc(a, b, ratio);
      }
    }
  }
  double volume_fraction(int a, int b) const {
    a = std::abs(a);
    b = std::abs(b);
    return a < table_size && b < table_size ? beta_table[a * table_size + b] : 0.0;
  }

  // Bonds to every neighbour with a positive weight that no notch cuts. k0 receives each bond's
  // stiffness before the surface correction, nx2 the squared x-component of its unit vector.
  // Reference lengths come from the integer grid offsets, so both directions hold identical values.
  void make_bonds(std::vector<double>& k0, std::vector<double>& nx2) {
    // neighbours within the horizon, plus the half cell the partial-volume band reaches
    const double reach = def.partial_volume_correction ? delta + 0.5 * dx : delta;
    const NeighborList nl = find_neighbors(grid.x, grid.y, reach * (1 + 1e-9));
    const int count = n();
    const double v = volume.front();
    bonds.row.assign(count + 1, 0);
    bonds.neighbor.reserve(nl.col.size());
    bonds.length_class.reserve(nl.col.size());
    bonds.grid_spacing = dx;
    k0.reserve(nl.col.size());
    nx2.reserve(nl.col.size());
    initial_weight.assign(count, 0.0);
    std::vector<double> notch_weight(count, 0.0);
    for (int i = 0; i < count; ++i) {
      for (int64_t b = nl.row[i]; b < nl.row[i + 1]; ++b) {
        const int32_t j = nl.col[b];
        const int di = grid.ix[j] - grid.ix[i], dj = grid.iy[j] - grid.iy[i];
        const double r2 = double(di) * di + double(dj) * dj;
        const double r = dx * std::sqrt(r2);
        const double beta = volume_fraction(di, dj);
        const double w = influence(def.influence, r, delta);
        if (beta <= 0.0 || w <= 0.0) continue;
        const Vec2 pi(grid.x[i], grid.y[i]), pj(grid.x[j], grid.y[j]);
        bool cut = false;
        for (const NotchDef& notch : def.notches) cut = cut || notch_cuts_bond(pi, pj, notch.p1, notch.p2, 1e-9 * dx * dx);
        if (cut) {
          notch_weight[i] += beta;  // counted as broken when the scene asks for it
          continue;
        }
        bonds.neighbor.push_back(j);
        bonds.length_class.push_back(static_cast<uint8_t>(r2));
        k0.push_back(c * w * beta * v * v);
        nx2.push_back(double(di) * di / r2);
        // the factor depends on the offset's length only, so one entry per length class
        if (class_weight.size() <= static_cast<size_t>(r2)) class_weight.resize(static_cast<size_t>(r2) + 1, 0.0);
        class_weight[static_cast<size_t>(r2)] = beta;
      }
      bonds.row[i + 1] = static_cast<int64_t>(bonds.neighbor.size());
    }
    // the damage pass weighs bonds by their length class: the initial weights are summed from
    // the same table, so a particle with every bond intact has damage exactly 0
    for (int i = 0; i < count; ++i) {
      double sum = 0.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) sum += class_weight[bonds.length_class[b]];
      initial_weight[i] = sum + (def.damage == FlexBodyDef::Damage::kIncludeNotch ? notch_weight[i] : 0.0);
    }
    bonds.neighbor.shrink_to_fit();
    bonds.length_class.shrink_to_fit();
    bonds.make_length_table();
    bonds.make_offsets();
    bonds.broken.assign(bonds.neighbor.size(), 0);
  }

  // Final bond stiffness k = k0 G. Surface correction, energy method of Madenci & Oterkus
  // (2014): under uniaxial stress along x (then y) each particle's factor is continuum /
  // discrete energy density; a bond takes the mean of its ends' factors per axis, combined
  // along its direction n as G = ((n_x / G_x)^2 + (n_y / G_y)^2)^(-1/2). Uniaxial stress
  // (H = diag(1, -1/3), the contraction of nu = 1/3) rather than uniaxial strain, so that a free
  // edge loaded along itself, the usual case, is calibrated in the state it is in.
  void set_stiffness(const std::vector<double>& k0, const std::vector<double>& nx2) {
    const int count = n();
    const double v = volume.front();
    std::vector<double> gx(count, 1.0), gy(count, 1.0);
    if (def.surface_correction) {
      const double w_cont = uniaxial_stress_energy_density(c, def.thickness, delta, 1.0);
      for (int i = 0; i < count; ++i) {
        double wx = 0.0, wy = 0.0;
        for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
          // linearised stretch n . H n: n_x^2 - n_y^2 / 3 along x, n_y^2 - n_x^2 / 3 along y
          const double cx = nx2[b], cy = 1.0 - cx;
          const double sx = cx - cy / 3.0, sy = cy - cx / 3.0;
          wx += 0.25 * k0[b] / bonds.inv_length(b) * sx * sx;
          wy += 0.25 * k0[b] / bonds.inv_length(b) * sy * sy;
        }
        if (wx > 0.0) gx[i] = w_cont * v / wx;
        if (wy > 0.0) gy[i] = w_cont * v / wy;
      }
    }
    bonds.stiffness.resize(k0.size());
    for (int i = 0; i < count; ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const int32_t j = bonds.neighbor[b];
        const double mean_x = 0.5 * (gx[i] + gx[j]), mean_y = 0.5 * (gy[i] + gy[j]);
        const double cx = nx2[b], cy = 1.0 - cx;
        bonds.stiffness[b] = static_cast<float>(k0[b] / std::sqrt(cx / (mean_x * mean_x) + cy / (mean_y * mean_y)));
      }
    }
  }

  // State-based bonds carry their weight w beta = k0 / (c V^2) (identical in both directions, as
  // k0 is), times the LPS surface correction's bond factor when surface_correction is on
  // (state_based_surface.h: the energy-method factors of set_stiffness do not apply to the LPS,
  // whose energy does not change when all of a particle's weights scale alike); the weighted
  // volumes follow from them.
  void set_state_weights(const std::vector<double>& k0) {
    const double v = volume.front();
    std::vector<double> weight(k0.size());
    for (size_t b = 0; b < k0.size(); ++b) weight[b] = k0[b] / (c * v * v);
    lps.shear_modulus.assign(n(), lps.mu);
    if (def.surface_correction) {
      // reference unit vectors from the integer grid offsets
      std::vector<double> nx(k0.size()), ny(k0.size());
      for (int i = 0; i < n(); ++i) {
        for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
          const int32_t j = bonds.neighbor[b];
          const double di = grid.ix[j] - grid.ix[i], dj = grid.iy[j] - grid.iy[i];
          const double r = std::sqrt(di * di + dj * dj);
          nx[b] = di / r;
          ny[b] = dj / r;
        }
      }
      const LpsSurfaceFactors factors = lps_surface_factors(bonds, weight, nx, ny);
      for (size_t b = 0; b < k0.size(); ++b) weight[b] *= factors.bond[b];
      for (int i = 0; i < n(); ++i) lps.shear_modulus[i] = lps.mu * factors.shear[i];
    }
    bonds.stiffness.resize(k0.size());
    for (size_t b = 0; b < k0.size(); ++b) bonds.stiffness[b] = static_cast<float>(weight[b]);
    update_weighted_volumes(bonds, lps);
  }

  // Region loads: imposed motions become prescribed coordinates, tractions and body forces
  // become per-particle force scales.
  void collect_loads() {
    for (const RegionLoadDef& load : def.loads) {
      std::vector<int> inside;
      for (int i = 0; i < n(); ++i)
        if (load.region.contains(Vec2(grid.x[i], grid.y[i]))) inside.push_back(i);
      if (inside.empty()) {
        warnings.push_back("load '" + load.name + "' selects no particle");
        continue;
      }
      switch (load.kind) {
        case RegionLoadDef::Kind::kPrescribedVelocity:
        case RegionLoadDef::Kind::kPrescribedDisplacement: {
          const bool velocity = load.kind == RegionLoadDef::Kind::kPrescribedVelocity;
          for (int i : inside) {
            for (int comp = 0; comp < 2; ++comp) {
              const std::optional<TimeFunction>& f = comp == 0 ? load.fx : load.fy;
              if (!f) continue;
              PrescribedCoordinate pc;
              pc.coordinate = offset + 2 * i + comp;
              pc.reference = reference[2 * i + comp];
              pc.displacement = velocity ? f->antiderivative() : *f;
              prescribed.push_back(pc);
            }
          }
          break;
        }
        case RegionLoadDef::Kind::kTraction: {
          // traction [Pa] on the boundary the region covers: total force = traction * length * t,
          // length = particles * dx / layers, layers = particle rows across the region (the
          // smaller of its numbers of distinct grid columns and rows)
          std::set<int32_t> cols, rows;
          for (int i : inside) {
            cols.insert(grid.ix[i]);
            rows.insert(grid.iy[i]);
          }
          const double layers = static_cast<double>(std::min(cols.size(), rows.size()));
          loads.push_back({inside, def.thickness * dx / layers, load.fx, load.fy});
          break;
        }
        case RegionLoadDef::Kind::kBodyForce:
          loads.push_back({inside, volume.front(), load.fx, load.fy});
          break;
      }
    }
  }

  const double* pos(const Eigen::VectorXd& q) const { return q.data() + offset; }
  int n() const { return grid.size(); }
};

PdBody::PdBody(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PdBody::~PdBody() = default;

std::unique_ptr<PdBody> PdBody::build(const FlexBodyDef& def, int coordinate_offset) {
  auto m = std::make_unique<Impl>();
  m->def = def;
  m->offset = coordinate_offset;
  const PdMaterialDef& mat = def.material;

  // reject what cannot be built, naming the key
  auto require = [&](bool ok, const std::string& key, const std::string& message) {
    if (!ok) throw InputError(with_key(def.where, key), "flex body '" + def.name + "': " + message);
  };
  require(def.shape.kind == ShapeDef::Kind::kBox || def.shape.kind == ShapeDef::Kind::kCircle ||
              def.shape.kind == ShapeDef::Kind::kPolygon || def.shape.kind == ShapeDef::Kind::kBar,
          "shape", "needs a box, circle, polygon or bar shape");
  require(def.grid_spacing > 0.0, "grid_spacing", "grid_spacing must be positive");
  require(def.thickness > 0.0, "thickness", "thickness must be positive");
  require(def.horizon_ratio >= 1.0, "horizon_ratio", "horizon_ratio must be at least 1");
  // bonds store their squared grid offset in 8 bits
  require(def.horizon_ratio <= kMaxHorizonRatio, "horizon_ratio",
          "horizon_ratio must be at most " + std::to_string(int(kMaxHorizonRatio)));
  require(mat.youngs_modulus > 0.0, "material.youngs_modulus", "youngs_modulus must be positive");
  require(mat.density > 0.0, "material.density", "density must be positive");
  require(mat.fracture_energy >= 0.0, "material.fracture_energy", "fracture_energy must not be negative");
  require(mat.critical_stretch >= 0.0, "material.critical_stretch", "critical_stretch must not be negative");

  // refuse huge grids before allocating anything
  const double estimate = estimated_particle_count(def.shape, def.grid_spacing);
  if (estimate > kMaxParticles) {
    std::ostringstream msg;
    msg << "flex body '" << def.name << "': grid_spacing " << def.grid_spacing << " needs about "
        << static_cast<long long>(estimate) << " particles, more than the limit of "
        << static_cast<long long>(kMaxParticles) << "; raise grid_spacing";
    throw InputError(with_key(def.where, "grid_spacing"), msg.str());
  }

  // particles on the grid
  m->dx = def.grid_spacing;
  m->delta = def.horizon_ratio * def.grid_spacing;
  m->grid = fill_grid(def.shape, def.holes, m->dx);
  const int n = m->n();
  require(n > 0, "shape", "the shape holds no particle at this grid_spacing");
  const double v = m->dx * m->dx * def.thickness;
  m->reference.resize(2 * n);
  for (int i = 0; i < n; ++i) {
    m->reference[2 * i] = m->grid.x[i];
    m->reference[2 * i + 1] = m->grid.y[i];
  }
  m->volume.assign(n, v);
  m->mass.assign(n, mat.density * v);

  // material constants
  m->c = periflex::micromodulus(mat.youngs_modulus, def.thickness, m->delta, mat.plane_strain);
  m->fracture = def.fracture;
  m->s0 = std::numeric_limits<double>::infinity();
  m->state_based = mat.model == PdMaterialDef::Model::kStateBased;
  if (m->state_based) {
    const double nu = mat.poisson_ratio;
    require(nu > -1.0 && (mat.plane_strain ? nu < 0.5 : nu <= 0.5), "material.poisson_ratio",
            "the state-based model needs -1 < poisson_ratio < 0.5 (plane stress also 0.5)");
    m->lps.volume = v;
    m->lps.kappa = lps_bulk_modulus(mat.youngs_modulus, nu, mat.plane_strain);
    m->lps.mu = lps_shear_modulus(mat.youngs_modulus, nu);
  }
  if (mat.critical_stretch > 0.0) {
    m->s0 = mat.critical_stretch;
  } else if (mat.fracture_energy > 0.0 && m->state_based) {
    m->s0 = lps_critical_stretch_from_energy(mat.fracture_energy, mat.youngs_modulus, mat.poisson_ratio, m->delta,
                                             mat.plane_strain, def.influence);
  } else if (mat.fracture_energy > 0.0) {
    m->s0 = critical_stretch_from_energy(mat.fracture_energy, mat.youngs_modulus, m->delta, mat.plane_strain,
                                         def.influence);
  } else if (def.fracture) {
    m->warnings.push_back("fracture is on but neither fracture_energy nor critical_stretch is given; "
                          "bonds will not break");
  }
  if (!m->state_based && mat.poisson_ratio >= 0.0) {
    const double implied = implied_poisson_ratio(mat.plane_strain);
    if (std::abs(mat.poisson_ratio - implied) > 1e-3) {
      std::ostringstream msg;
      msg << "bond-based peridynamics implies a Poisson ratio of "
          << (mat.plane_strain ? "1/4 in plane strain" : "1/3 in plane stress") << "; the stated "
          << mat.poisson_ratio << " is not represented";
      m->warnings.push_back(msg.str());
    }
  }

  // no-fail flags, bonds, surface correction, loads
  m->no_fail.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const Vec2 p(m->grid.x[i], m->grid.y[i]);
    for (const ShapeDef& region : def.no_fail_regions) m->no_fail[i] |= region.contains(p) ? 1 : 0;
  }
  m->build_beta_table();
  std::vector<double> k0, nx2;
  m->make_bonds(k0, nx2);
  if (m->state_based)
    m->set_state_weights(k0);
  else
    m->set_stiffness(k0, nx2);
  m->collect_loads();

  m->bond_damping = def.bond_damping;
  m->global_damping = def.global_damping;
  return std::unique_ptr<PdBody>(new PdBody(std::move(m)));
}

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

double PdBody::critical_time_step() const {
  const Impl& m = *impl_;
  const BondStore& b = m.bonds;
  if (m.state_based) return state_based_critical_time_step(b, m.lps, m.mass);
  // Silling & Askari (2005): dt < sqrt(2 rho / sum_j C_ij V_j / |xi|) = sqrt(2 m_i / sum_b k_b / |xi_b|)
  double dt = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.n(); ++i) {
    double sum = 0.0;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) sum += double(b.stiffness[k]) * b.inv_length(k);
    if (sum > 0.0) dt = std::min(dt, std::sqrt(2.0 * m.mass[i] / sum));
  }
  return dt;
}

void PdBody::add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) {
  Impl& m = *impl_;
  double* force = g.data() + m.offset;
  const double eta_over_e = m.bond_damping / m.def.material.youngs_modulus;

  // with fracture on the force loop also sees the stretch: an evaluation that breaks bonds leaves
  // out those past s0; one that holds every bond leaves the row maxima for update_fracture and
  // copies the positions it saw, chunk by chunk, so update_fracture knows they are its own.
  const double* pos = m.pos(q);
  const double* vel = qd.data() + m.offset;
  if (m.tracks_stretch()) {
    const bool breaking_here = !m.state_based && m.break_timing == BreakTiming::kInEvaluation;
    if (!breaking_here) m.stretch_cache_pos.resize(2 * m.n());
    m.stretch_cache_valid = !breaking_here;
    double* seen = breaking_here ? nullptr : m.stretch_cache_pos.data();
    if (m.state_based) {
      // state-based bonds break after the step (update_fracture), from these row maxima
      m.stretch_cache_most.resize(m.n());
      add_state_based_forces(m.bonds, m.lps, pos, vel, eta_over_e, force, m.stretch_cache_most.data(), seen);
    } else if (m.break_timing == BreakTiming::kAfterStep) {
      m.stretch_cache_most.resize(m.n());
      if (eta_over_e > 0.0)
        add_damped_bond_forces(m.bonds, pos, vel, eta_over_e, force, m.stretch_cache_most.data(), seen);
      else
        add_bond_forces(m.bonds, pos, force, m.stretch_cache_most.data(), seen);
    } else {
      m.row_broke.resize(m.n(), 0);
      BreakingEvaluation breaking;
      breaking.s0 = m.s0;
      breaking.no_fail = m.def.no_fail_regions.empty() ? nullptr : m.no_fail.data();
      breaking.row_broke = m.row_broke.data();
      add_bond_forces_breaking(m.bonds, pos, vel, eta_over_e, breaking, force, seen);
      double energy = 0.0;
      const double half_kick = t == m.step_end ? m.half_kick : 0.0;
      const long broken = settle_broken_bonds(m.bonds, pos, vel, half_kick, m.row_broke.data(), energy);
      m.pending_broken += broken;
      m.pending_energy += energy;
      m.broken_pairs += broken;
    }
  } else if (m.state_based) {
    add_state_based_forces(m.bonds, m.lps, pos, vel, eta_over_e, force, nullptr, nullptr);
  } else if (eta_over_e > 0.0) {
    add_damped_bond_forces(m.bonds, pos, vel, eta_over_e, force);
  } else {
    add_bond_forces(m.bonds, pos, force);
  }

  // mass-proportional damping -alpha m v
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
    for (int i : load.particles) {
      force[2 * i] += fx;
      force[2 * i + 1] += fy;
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
  if (!m.state_based) {
    for (int i = 0; i < m.n(); ++i) {
      couple(i, i);
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
        if (!bonds.broken[b]) couple(i, bonds.neighbor[b]);
    }
    return true;
  }
  // state-based: the particles within two intact bonds, each once per row (a stamp per particle)
  std::vector<int> seen(m.n(), -1);
  for (int i = 0; i < m.n(); ++i) {
    auto reach = [&](int j) {
      if (seen[j] == i) return;
      seen[j] = i;
      couple(i, j);
    };
    reach(i);
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const int j = bonds.neighbor[b];
      reach(j);
      for (int64_t d = bonds.row[j]; d < bonds.row[j + 1]; ++d)
        if (!bonds.broken[d]) reach(bonds.neighbor[d]);
    }
  }
  return true;
}

double PdBody::potential_energy(const Eigen::VectorXd& q) const {
  if (impl_->state_based) return state_based_strain_energy(impl_->bonds, impl_->lps, impl_->pos(q));
  return bond_strain_energy(impl_->bonds, impl_->pos(q));
}

double PdBody::dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
  const Impl& m = *impl_;
  const double* vel = qd.data() + m.offset;
  double power = 0.0;
  const double eta_over_e = m.bond_damping / m.def.material.youngs_modulus;
  if (eta_over_e > 0.0 && m.state_based)
    power += state_based_damping_power(m.bonds, m.lps, m.pos(q), vel, eta_over_e);
  else if (eta_over_e > 0.0)
    power += bond_damping_power(m.bonds, m.pos(q), vel, eta_over_e);
  if (m.global_damping > 0.0) {
    for (int i = 0; i < m.n(); ++i)
      power += m.global_damping * m.mass[i] * (vel[2 * i] * vel[2 * i] + vel[2 * i + 1] * vel[2 * i + 1]);
  }
  return power;
}

double PdBody::external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const {
  const Impl& m = *impl_;
  const double* vel = qd.data() + m.offset;
  double power = 0.0;
  for (const AppliedLoad& load : m.loads) {
    const double fx = load.fx ? load.scale * (*load.fx)(t) : 0.0;
    const double fy = load.fy ? load.scale * (*load.fy)(t) : 0.0;
    for (int i : load.particles) power += fx * vel[2 * i] + fy * vel[2 * i + 1];
  }
  return power;
}

bool PdBody::breaks_in_evaluation() const {
  return impl_->tracks_stretch() && !impl_->state_based && impl_->break_timing == BreakTiming::kInEvaluation;
}

FractureUpdate PdBody::take_evaluation_breaks() {
  Impl& m = *impl_;
  FractureUpdate update;
  update.bonds_broken = m.pending_broken;
  update.energy_released = m.pending_energy;
  m.pending_broken = 0;
  m.pending_energy = 0.0;
  return update;
}

FractureUpdate PdBody::update_fracture(const Eigen::VectorXd& q) {
  Impl& m = *impl_;
  // what the force evaluations since the last update broke (their forces are without them)
  FractureUpdate update = take_evaluation_breaks();
  if (!m.fracture || !std::isfinite(m.s0)) return update;
  const uint8_t* no_fail = m.def.no_fail_regions.empty() ? nullptr : m.no_fail.data();
  // the bonds break here: from the row maxima of the last force evaluation (which held every
  // bond) when it saw exactly these positions
  const bool cached = m.stretch_cache_valid &&
                      std::equal(m.stretch_cache_pos.begin(), m.stretch_cache_pos.end(), m.pos(q));
  m.stretch_cache_valid = false;
  // state-based: the strain energy does not split into bonds, but a broken bond changes the energy
  // of its two ends only, and both are rows whose largest stretch is near s0 (outside no-fail
  // regions): the energy released is the energy of those rows before minus after
  std::vector<int> candidates;
  double before = 0.0;
  if (m.state_based) {
    std::vector<float> most;
    if (!cached) {
      most.resize(m.n());
      max_bond_stretch(m.bonds, m.pos(q), most.data());
    }
    for (int i = 0; i < m.n(); ++i) {
      const double top = cached ? m.stretch_cache_most[i] : double(most.empty() ? 0.0f : most[i]);
      // float row maxima (when not cached) are within 1e-7 relative of the exact ones
      if (top > m.s0 * (1.0 - 1e-6) - 1e-12 && !(no_fail && no_fail[i])) candidates.push_back(i);
    }
    if (!candidates.empty()) before = state_based_rows_energy(m.bonds, m.lps, m.pos(q), candidates);
  }
  double energy = 0.0;
  const long broken = break_stretched_bonds(m.bonds, m.pos(q), m.s0, no_fail, energy,
                                            cached ? m.stretch_cache_most.data() : nullptr);
  if (m.state_based) {
    energy = 0.0;
    if (broken > 0) {
      // the weighted volumes count intact bonds only
      refresh_weighted_volumes(m.bonds, m.lps, candidates);
      energy = before - state_based_rows_energy(m.bonds, m.lps, m.pos(q), candidates);
    }
  }
  m.broken_pairs += broken;
  update.bonds_broken += broken;
  update.energy_released += energy;
  update.forces_stale = broken > 0;
  return update;
}

FractureUpdate PdBody::cut_bonds(const Eigen::VectorXd& q, const std::vector<double>& positions, const Vec2& a,
                                 const Vec2& b) {
  Impl& m = *impl_;
  FractureUpdate update;
  const double* p = positions.size() == 2 * static_cast<size_t>(m.n()) ? positions.data() : m.pos(q);
  const double before = potential_energy(q);
  // each pair once (i < j), both stored directions broken together
  BondStore& bonds = m.bonds;
  std::vector<int> touched;
  for (int i = 0; i < m.n(); ++i) {
    const Vec2 pi(p[2 * i], p[2 * i + 1]);
    for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) {
      const int j = bonds.neighbor[k];
      if (j <= i || bonds.broken[k]) continue;
      if (!notch_cuts_bond(pi, Vec2(p[2 * j], p[2 * j + 1]), a, b, 1e-9 * m.dx * m.dx)) continue;
      // the stiffness is kept, as for a bond that breaks under load: a restored state heals it
      bonds.broken_stiffness.emplace_back(k, bonds.stiffness[k]);
      bonds.broken[k] = 1;
      bonds.stiffness[k] = 0.0f;
      for (int64_t r = bonds.row[j]; r < bonds.row[j + 1]; ++r) {
        if (bonds.neighbor[r] != i) continue;
        bonds.broken_stiffness.emplace_back(r, bonds.stiffness[r]);
        bonds.broken[r] = 1;
        bonds.stiffness[r] = 0.0f;
      }
      ++update.bonds_broken;
      if (touched.empty() || touched.back() != i) touched.push_back(i);
      touched.push_back(j);
    }
  }
  if (update.bonds_broken == 0) return update;
  // state-based: the weighted volumes count intact bonds only
  if (m.state_based) {
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    refresh_weighted_volumes(m.bonds, m.lps, touched);
  }
  m.stretch_cache_valid = false;
  m.broken_pairs += update.bonds_broken;
  update.energy_released = before - potential_energy(q);
  update.forces_stale = true;
  return update;
}

void PdBody::save_state(FlexState& out) const {
  const Impl& m = *impl_;
  const BondStore& b = m.bonds;
  // the broken flags as bits, 64 stored directions to a word
  const int64_t count = b.directed_count();
  out.broken_bits.assign(static_cast<size_t>((count + 63) / 64), 0);
  uint64_t* bits = out.broken_bits.data();
  const uint8_t* broken = b.broken.data();
  const int64_t words = static_cast<int64_t>(out.broken_bits.size());
#pragma omp parallel for schedule(static) if (count >= (1 << 20))
  for (int64_t w = 0; w < words; ++w) {
    uint64_t word = 0;
    const int64_t end = std::min<int64_t>(64, count - 64 * w);
    for (int64_t k = 0; k < end; ++k) word |= static_cast<uint64_t>(broken[64 * w + k] != 0) << k;
    bits[w] = word;
  }
  out.broken_pairs = m.broken_pairs;
  out.pending_broken = m.pending_broken;
  out.pending_energy = m.pending_energy;
  out.weighted_volume.clear();
  out.shear_coef.clear();
  if (m.state_based) {
    out.weighted_volume = m.lps.weighted_volume;
    out.shear_coef = m.lps.shear_coef;
  }
}

void PdBody::restore_state(const FlexState& in) {
  Impl& m = *impl_;
  BondStore& b = m.bonds;
  const int64_t count = b.directed_count();
  if (in.broken_bits.size() != static_cast<size_t>((count + 63) / 64) ||
      (m.state_based && (in.weighted_volume.size() != static_cast<size_t>(m.n()) ||
                         in.shear_coef.size() != static_cast<size_t>(m.n())))) {
    throw std::invalid_argument("state of flexible body '" + m.def.name + "' does not match its bonds");
  }
  // bonds broken now but intact in the state heal to the stiffness they had
  const uint64_t* bits = in.broken_bits.data();
  const auto broken_in_state = [&](int64_t k) { return ((bits[k / 64] >> (k % 64)) & 1u) != 0; };
  std::vector<std::pair<int64_t, float>> kept;
  kept.reserve(b.broken_stiffness.size());
  for (const auto& [k, stiffness] : b.broken_stiffness) {
    if (broken_in_state(k)) {
      kept.push_back({k, stiffness});
    } else {
      b.broken[k] = 0;
      b.stiffness[k] = stiffness;
    }
  }
  // bonds broken in the state but intact now break, keeping their stiffness (whole words of
  // intact bonds are skipped: before fracture this is a pass over the bits alone)
  for (size_t w = 0; w < in.broken_bits.size(); ++w) {
    if (in.broken_bits[w] == 0) continue;
    const int64_t end = std::min<int64_t>(64 * static_cast<int64_t>(w) + 64, count);
    for (int64_t k = 64 * static_cast<int64_t>(w); k < end; ++k) {
      if (!broken_in_state(k) || b.broken[k]) continue;
      kept.push_back({k, b.stiffness[k]});
      b.broken[k] = 1;
      b.stiffness[k] = 0.0f;
    }
  }
  b.broken_stiffness = std::move(kept);
  m.broken_pairs = in.broken_pairs;
  m.pending_broken = in.pending_broken;
  m.pending_energy = in.pending_energy;
  if (m.state_based) {
    m.lps.weighted_volume = in.weighted_volume;
    m.lps.shear_coef = in.shear_coef;
  }
  m.stretch_cache_valid = false;
}

void PdBody::damage(std::vector<float>& out) const {
  const Impl& m = *impl_;
  const BondStore& b = m.bonds;
  out.resize(m.n());
  // 1 - intact weight / initial weight, the weight of a bond being its partial-volume factor
  const int n = m.n();
  const double* weight = m.class_weight.data();
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (int i = 0; i < n; ++i) {
    double intact = 0.0;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) intact += b.broken[k] ? 0.0 : weight[b.length_class[k]];
    const double d = m.initial_weight[i] > 0.0 ? 1.0 - intact / m.initial_weight[i] : 0.0;
    out[i] = static_cast<float>(std::clamp(d, 0.0, 1.0));
  }
}

void PdBody::max_stretch(const Eigen::VectorXd& q, std::vector<float>& out) const {
  out.resize(impl_->n());
  max_bond_stretch(impl_->bonds, impl_->pos(q), out.data());
}

void PdBody::strain_energy_density(const Eigen::VectorXd& q, std::vector<double>& out) const {
  const Impl& m = *impl_;
  const BondStore& b = m.bonds;
  const double* p = m.pos(q);
  out.resize(m.n());
  if (m.state_based) return state_based_energy_density(b, m.lps, p, out.data());
  for (int i = 0; i < m.n(); ++i) {
    double sum = 0.0;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int32_t j = b.neighbor[k];
      const double dx = p[2 * j] - p[2 * i], dy = p[2 * j + 1] - p[2 * i + 1];
      const double s = std::sqrt(dx * dx + dy * dy) * b.inv_length(k) - 1.0;
      sum += 0.25 * double(b.stiffness[k]) * s * s / b.inv_length(k);
    }
    out[i] = sum / m.volume[i];
  }
}

size_t PdBody::memory_bytes() const {
  const Impl& m = *impl_;
  const size_t per_particle_doubles = m.reference.capacity() + m.mass.capacity() + m.volume.capacity() +
                                      m.grid.x.capacity() + m.grid.y.capacity() + m.initial_weight.capacity() +
                                      m.stretch_cache_pos.capacity() + m.stretch_cache_most.capacity() +
                                      m.lps.weighted_volume.capacity() + m.lps.shear_coef.capacity() + m.lps.shear_modulus.capacity() +
                                      m.lps.bulk_coef.capacity() + m.lps.dilatation.capacity() +
                                      m.lps.records.capacity();
  const size_t per_particle_bytes = m.no_fail.capacity() + m.row_broke.capacity();
  return m.bonds.bytes() + per_particle_doubles * sizeof(double) +
         (m.grid.ix.capacity() + m.grid.iy.capacity()) * sizeof(int32_t) + per_particle_bytes;
}

int PdBody::nearest_particle(const Vec2& point) const {
  const Impl& m = *impl_;
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.n(); ++i) {
    const double dx = m.grid.x[i] - point.x(), dy = m.grid.y[i] - point.y();
    const double d2 = dx * dx + dy * dy;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

std::vector<int> PdBody::particles_in(const ShapeDef& region) const {
  const Impl& m = *impl_;
  std::vector<int> out;
  for (int i = 0; i < m.n(); ++i)
    if (region.contains(Vec2(m.grid.x[i], m.grid.y[i]))) out.push_back(i);
  return out;
}

void PdBody::bond_pairs(std::vector<std::pair<int, int>>& out, size_t max_pairs) const {
  const BondStore& b = impl_->bonds;
  out.clear();
  for (int i = 0; i < b.particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      if (b.broken[k] || b.neighbor[k] <= i) continue;
      if (out.size() >= max_pairs) {
        out.clear();
        return;
      }
      out.emplace_back(i, b.neighbor[k]);
    }
  }
}

}  // namespace periflex
