#include "pd/bond_based_law.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/parallel_chunks.h"
#include "pd/pd_material.h"

namespace periflex {

BondBasedLaw::BondBasedLaw(const FlexBodyDef& def, double horizon, std::vector<std::string>& warnings) {
  const PdMaterialDef& mat = def.material;
  s0_ = material_critical_stretch(
      def,
      [&](double g0) {
        return critical_stretch_from_energy(g0, mat.youngs_modulus, horizon, mat.plane_strain, def.influence);
      },
      warnings);
  if (mat.poisson_ratio >= 0.0) {
    const double implied = implied_poisson_ratio(mat.plane_strain);
    if (std::abs(mat.poisson_ratio - implied) > 1e-3) {
      std::ostringstream msg;
      msg << "bond-based peridynamics implies a Poisson ratio of "
          << (mat.plane_strain ? "1/4 in plane strain" : "1/3 in plane stress") << "; the stated "
          << mat.poisson_ratio << " is not represented";
      warnings.push_back(msg.str());
    }
  }
}

// Surface correction, energy method of Madenci & Oterkus (2014): under uniaxial stress along x
// (then y) each particle's factor is continuum / discrete energy density; a bond takes the mean of
// its ends' factors per axis, combined along its direction n as G = ((n_x / G_x)^2 + (n_y / G_y)^2)^(-1/2).
// Uniaxial stress (H = diag(1, -1/3), the contraction of nu = 1/3) rather than uniaxial strain, so
// that a free edge loaded along itself, the usual case, is calibrated in the state it is in.
void set_bond_stiffness(const LawSetup& setup, BondStore& bonds) {
  const std::vector<double>& k0 = setup.k0;
  const std::vector<double>& nx2 = setup.nx2;
  const int count = bonds.particle_count();
  const double v = setup.volume;
  std::vector<double> gx(count, 1.0), gy(count, 1.0);
  // each row on its own, on the team's threads: the same bits on any thread count
  if (setup.def.surface_correction) {
    const double w_cont = uniaxial_stress_energy_density(setup.micromodulus, setup.def.thickness, setup.horizon, 1.0);
    parallel_chunks(count, [&](int64_t, int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        double wx = 0.0, wy = 0.0;
        for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
          // linearised stretch n . H n: n_x^2 - n_y^2 / 3 along x, n_y^2 - n_x^2 / 3 along y
          const double cx = nx2[b], cy = 1.0 - cx;
          const double sx = cx - cy / 3.0, sy = cy - cx / 3.0;
          wx += 0.25 * k0[b] / bonds.inv_length(b) * sx * sx;
          wy += 0.25 * k0[b] / bonds.inv_length(b) * sy * sy;
        }
        // the continuum's energy in the particle's own material (materials by block)
        const double vi = (setup.volumes ? setup.volumes[i] : v) * (setup.modulus_ratio ? setup.modulus_ratio[i] : 1.0);
        if (wx > 0.0) gx[i] = w_cont * vi / wx;
        if (wy > 0.0) gy[i] = w_cont * vi / wy;
      }
    });
  }
  bonds.coefficient.resize(k0.size());
  parallel_chunks(count, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const int32_t j = bonds.neighbor[b];
        const double mean_x = 0.5 * (gx[i] + gx[j]), mean_y = 0.5 * (gy[i] + gy[j]);
        const double cx = nx2[b], cy = 1.0 - cx;
        bonds.coefficient[b] = static_cast<float>(k0[b] / std::sqrt(cx / (mean_x * mean_x) + cy / (mean_y * mean_y)));
      }
    }
  });
}

double spring_critical_time_step(const BondStore& b, const BondState& live, const std::vector<double>& masses) {
  // dt < sqrt(2 rho / sum_j C_ij V_j / |xi|) = sqrt(2 m_i / sum_b k_b / |xi_b|)
  double dt = std::numeric_limits<double>::infinity();
  for (int i = 0; i < b.particle_count(); ++i) {
    double sum = 0.0;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) sum += double(live.stiffness[k]) * b.inv_length(k);
    if (sum > 0.0) dt = std::min(dt, std::sqrt(2.0 * masses[i] / sum));
  }
  return dt;
}

void BondBasedLaw::set_coefficients(const LawSetup& setup, BondStore& bonds) { set_bond_stiffness(setup, bonds); }

double BondBasedLaw::critical_time_step(const BondStore& bonds, const BondState& live,
                                        const std::vector<double>& masses) const {
  return spring_critical_time_step(bonds, live, masses);
}

void BondBasedLaw::add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) {
  if (e.eta_over_e > 0.0)
    add_damped_bond_forces(bonds, live, e.pos, e.vel, e.eta_over_e, e.force, e.row_max, e.pos_copy);
  else
    add_bond_forces(bonds, live, e.pos, e.force, e.row_max, e.pos_copy);
}

long BondBasedLaw::add_forces_breaking(const BondStore& bonds, BondState& live, const LawEvaluation& e,
                                       const uint8_t* no_fail, std::vector<uint8_t>& row_broke, double half_kick,
                                       double& energy) {
  row_broke.resize(bonds.particle_count(), 0);
  BreakingEvaluation breaking;
  breaking.s0 = s0_;
  breaking.no_fail = no_fail;
  breaking.row_broke = row_broke.data();
  add_bond_forces_breaking(bonds, live, e.pos, e.vel, e.eta_over_e, breaking, e.force, e.pos_copy);
  return settle_broken_bonds(bonds, live, e.pos, e.vel, half_kick, row_broke.data(), energy);
}

double BondBasedLaw::strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const {
  return bond_strain_energy(bonds, live, pos);
}

double BondBasedLaw::damping_power(const BondStore& bonds, const BondState& live, const double* pos,
                                   const double* vel, double eta_over_e) const {
  return bond_damping_power(bonds, live, pos, vel, eta_over_e);
}

void BondBasedLaw::energy_density(const BondStore& b, const BondState& live, const double* p,
                                  const std::vector<double>& volumes, double* out) const {
  // (1/V_i) sum_j k |xi| s^2 / 4
  for (int i = 0; i < b.particle_count(); ++i) {
    double sum = 0.0;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int32_t j = b.neighbor[k];
      const double dx = p[2 * j] - p[2 * i], dy = p[2 * j + 1] - p[2 * i + 1];
      const double s = std::sqrt(dx * dx + dy * dy) * b.inv_length(k) - 1.0;
      sum += 0.25 * double(live.stiffness[k]) * s * s / b.inv_length(k);
    }
    out[i] = sum / volumes[i];
  }
}

BreakResult BondBasedLaw::break_bonds(const BondStore& bonds, BondState& live, const double* pos,
                                      const uint8_t* no_fail, const double* row_max) {
  BreakResult result;
  result.pairs = break_stretched_bonds(bonds, live, pos, s0_, no_fail, result.energy, row_max);
  return result;
}

}  // namespace periflex
