#include "pd/state_based_law.h"

#include <algorithm>
#include <cmath>

#include "pd/state_based_material.h"
#include "pd/state_based_surface.h"

namespace periflex {

StateBasedLaw::StateBasedLaw(const FlexBodyDef& def, double horizon, double volume,
                             std::vector<std::string>& warnings) {
  const PdMaterialDef& mat = def.material;
  const double nu = mat.poisson_ratio;
  require_material(def, nu > -1.0 && (mat.plane_strain ? nu < 0.5 : nu <= 0.5), "poisson_ratio",
                   "the state-based model needs -1 < poisson_ratio < 0.5 (plane stress also 0.5)");
  lps_.volume = volume;
  lps_.kappa = lps_bulk_modulus(mat.youngs_modulus, nu, mat.plane_strain);
  lps_.mu = lps_shear_modulus(mat.youngs_modulus, nu);
  s0_ = material_critical_stretch(
      def,
      [&](double g0) {
        return lps_critical_stretch_from_energy(g0, mat.youngs_modulus, nu, horizon, mat.plane_strain,
                                                def.influence);
      },
      warnings);
}

// State-based bonds carry their weight w beta = k0 / (c V^2) (identical in both directions, as
// k0 is), times the LPS surface correction's bond factor when surface_correction is on
// (state_based_surface.h: the energy-method factors of the bond-based law do not apply to the LPS,
// whose energy does not change when all of a particle's weights scale alike); the weighted
// volumes follow from them.
void StateBasedLaw::set_coefficients(const LawSetup& setup, BondStore& bonds) {
  const std::vector<double>& k0 = setup.k0;
  const double c = setup.micromodulus, v = setup.volume;
  const int n = bonds.particle_count();
  std::vector<double> weight(k0.size());
  for (size_t b = 0; b < k0.size(); ++b) weight[b] = k0[b] / (c * v * v);
  lps_.shear_modulus.assign(n, lps_.mu);
  // a graded point file: the weights w beta r_i r_j follow from k0 = c w beta V_i V_j
  lps_.volume_ratio.clear();
  if (setup.volumes)
    for (int i = 0; i < n; ++i) lps_.volume_ratio.push_back(setup.volumes[i] / v);
  if (setup.def.surface_correction) {
    // reference unit vectors from the integer grid offsets (off the grid: from the positions)
    const ParticleGrid& grid = setup.grid;
    std::vector<double> nx(k0.size()), ny(k0.size());
    for (int i = 0; i < n; ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const int32_t j = bonds.neighbor[b];
        const double di = grid.on_grid ? grid.ix[j] - grid.ix[i] : grid.x[j] - grid.x[i];
        const double dj = grid.on_grid ? grid.iy[j] - grid.iy[i] : grid.y[j] - grid.y[i];
        const double r = std::sqrt(di * di + dj * dj);
        nx[b] = di / r;
        ny[b] = dj / r;
      }
    }
    const LpsSurfaceFactors factors = lps_surface_factors(bonds, weight, nx, ny);
    for (size_t b = 0; b < k0.size(); ++b) weight[b] *= factors.bond[b];
    for (int i = 0; i < n; ++i) lps_.shear_modulus[i] = lps_.mu * factors.shear[i];
  }
  bonds.coefficient.resize(k0.size());
  for (size_t b = 0; b < k0.size(); ++b) bonds.coefficient[b] = static_cast<float>(weight[b]);
  // the fields of the intact body: the body's live state starts from the same coefficients
  update_weighted_volumes(bonds, BondState::intact(bonds), lps_);
}

double StateBasedLaw::critical_time_step(const BondStore& bonds, const BondState& live,
                                         const std::vector<double>& masses) const {
  return state_based_critical_time_step(bonds, live, lps_, masses);
}

void StateBasedLaw::add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) {
  add_state_based_forces(bonds, live, lps_, e.pos, e.vel, e.eta_over_e, e.force, e.row_max, e.pos_copy);
}

double StateBasedLaw::strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const {
  return state_based_strain_energy(bonds, live, lps_, pos);
}

double StateBasedLaw::damping_power(const BondStore& bonds, const BondState& live, const double* pos,
                                    const double* vel, double eta_over_e) const {
  return state_based_damping_power(bonds, live, lps_, pos, vel, eta_over_e);
}

void StateBasedLaw::energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                                   const std::vector<double>&, double* out) const {
  state_based_energy_density(bonds, live, lps_, pos, out);
}

BreakResult StateBasedLaw::break_bonds(const BondStore& bonds, BondState& live, const double* pos,
                                       const uint8_t* no_fail, const double* row_max) {
  // candidates: the rows whose largest stretch is near s0 (outside no-fail regions)
  const int n = bonds.particle_count();
  std::vector<int> candidates;
  double before = 0.0;
  std::vector<float> most;
  if (!row_max) {
    most.resize(n);
    max_bond_stretch(bonds, live, pos, most.data());
  }
  for (int i = 0; i < n; ++i) {
    const double top = row_max ? row_max[i] : double(most.empty() ? 0.0f : most[i]);
    // float row maxima (when not cached) are within 1e-7 relative of the exact ones
    if (top > s0_ * (1.0 - 1e-6) - 1e-12 && !(no_fail && no_fail[i])) candidates.push_back(i);
  }
  if (!candidates.empty()) before = state_based_rows_energy(bonds, live, lps_, pos, candidates);
  BreakResult result;
  double bond_energy = 0.0;
  result.pairs = break_stretched_bonds(bonds, live, pos, s0_, no_fail, bond_energy, row_max);
  if (result.pairs > 0) {
    // the weighted volumes count intact bonds only
    refresh_weighted_volumes(bonds, live, lps_, candidates);
    result.energy = before - state_based_rows_energy(bonds, live, lps_, pos, candidates);
  }
  return result;
}

void StateBasedLaw::bonds_cut(const BondStore& bonds, const BondState& live, std::vector<int>& particles) {
  std::sort(particles.begin(), particles.end());
  particles.erase(std::unique(particles.begin(), particles.end()), particles.end());
  refresh_weighted_volumes(bonds, live, lps_, particles);
}

void StateBasedLaw::save(FlexState& out) const {
  out.weighted_volume = lps_.weighted_volume;
  out.shear_coef = lps_.shear_coef;
}

bool StateBasedLaw::state_fits(const FlexState& in, int particles, int64_t) const {
  return in.weighted_volume.size() == static_cast<size_t>(particles) &&
         in.shear_coef.size() == static_cast<size_t>(particles);
}

void StateBasedLaw::restore(const FlexState& in) {
  lps_.weighted_volume = in.weighted_volume;
  lps_.shear_coef = in.shear_coef;
}

size_t StateBasedLaw::memory_bytes() const {
  return (lps_.weighted_volume.capacity() + lps_.shear_coef.capacity() + lps_.shear_modulus.capacity() +
          lps_.volume_ratio.capacity() +
          lps_.bulk_coef.capacity() + lps_.dilatation.capacity() + lps_.records.capacity()) *
         sizeof(double);
}

}  // namespace periflex
