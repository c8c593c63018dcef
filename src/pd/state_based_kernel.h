// The bond loops of the 2D ordinary state-based model (LPS; constants in state_based_material.h,
// derivation in docs/peridynamics.md). It uses the body's BondStore as the bond-based model does,
// with one difference in meaning: `stiffness` holds each bond's weight w(|xi|) beta (influence times
// partial-volume factor), 0 once broken, so drawing, damage, stretch colouring and the fracture pass
// work on it unchanged. Positions and velocities are interleaved [x0 y0 x1 y1 ...].
//
// With a = (2 kappa - 4 mu_i) theta / m and b = 8 mu_i / m per particle (mu_i the shear modulus
// with the surface correction's factor, state_based_surface.h), the pair force along the bond is
//   f_ij = V^2 w beta ((a_i + a_j) |xi| + (b_i + b_j) e),  e = |y| - |xi|,
// the derivative of the energy; so a step is two passes over the bonds: dilatations, then forces.
#pragma once

#include <cstdint>
#include <vector>

#include "pd/bond_state.h"
#include "pd/bond_store.h"

namespace periflex {

// The LPS law's constants and its per-particle fields (what the bond loops read and write besides
// the bonds): the law owns one (state_based_law.h).
struct LpsFields {
  double volume = 0.0;                   // V of the grid cell [m^3] (thickness included)
  // r_i = V_i / V of each particle of a graded point file (empty: every particle has V). The bond
  // weights then hold w beta r_i r_j (the same bits both ways), so that the sums over a row weigh
  // each neighbour by its volume; weighted_volume holds V sum w beta r_i r_j |xi|^2 = r_i m_i, with
  // which the dilatation comes out exact, and the coefficients below take m_i = weighted_volume / r_i.
  std::vector<double> volume_ratio;
  double kappa = 0.0, mu = 0.0;          // 2D bulk and shear moduli [Pa]
  std::vector<double> shear_modulus;     // mu_i: mu times the surface correction's factor (empty: mu)
  std::vector<double> weighted_volume;   // m_i = V sum_j w beta |xi|^2 over intact bonds [m^5] (r_i m_i graded)
  std::vector<double> shear_coef;        // b_i = 8 mu_i / m_i (0 without intact bonds)
  // r_i (1 on the grid)
  double ratio(int i) const { return volume_ratio.empty() ? 1.0 : volume_ratio[i]; }
  std::vector<double> bulk_coef;         // a_i of the last force evaluation (scratch)
  std::vector<double> dilatation;        // theta_i of the last dilatation pass (scratch)
  std::vector<double> records;           // [x_0 y_0 a_0 b_0 x_1 ...] (scratch): a neighbour in one 32-byte load
};

// Allows (default) or forbids the hand-written AVX-512 row loops; without them the compiled
// loops run (AVX2 or baseline). The two agree to round-off; this is for tests and comparisons.
void set_state_based_avx512(bool enabled);

// Fills weighted_volume and shear_coef from the intact bonds (and shear_modulus with mu where it is
// empty); call again after bonds break.
void update_weighted_volumes(const BondStore& bonds, const BondState& live, LpsFields& lps);

// The same for the listed particles only (those whose bonds just broke).
void refresh_weighted_volumes(const BondStore& bonds, const BondState& live, LpsFields& lps,
                              const std::vector<int>& particles);

// theta_i = (2 V / m_i) sum_j w beta |xi| e into lps.dilatation.
void compute_dilatations(const BondStore& bonds, const BondState& live, LpsFields& lps, const double* pos);

// force_i += sum_j f_ij e_ij (see above), plus, with eta_over_e > 0, a viscous pair force
// V^2 w beta (b_i + b_j) eta_over_e de/dt along the bond. row_max and pos_copy as add_bond_forces
// (the largest stretch over each row's intact bonds; a copy of pos).
void add_state_based_forces(const BondStore& bonds, const BondState& live, LpsFields& lps, const double* pos,
                            const double* vel,
                            double eta_over_e, double* force, double* row_max = nullptr, double* pos_copy = nullptr);

// Strain energy density W_i [J/m^3] of each particle into out (size n).
void state_based_energy_density(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                                double* out);

// Strain energy sum_i V W_i [J], summed in a fixed order (the same bits on any thread count).
double state_based_strain_energy(const BondStore& bonds, const BondState& live, const LpsFields& lps,
                                 const double* pos);

// Strain energy sum V W_i over the listed particles only [J]: breaking a bond changes the energy
// of its two ends alone, so the energy a fracture update releases is this sum before minus after.
double state_based_rows_energy(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                               const std::vector<int>& particles);

// Power the viscous pair forces remove: sum over pairs V^2 w beta (b_i + b_j) eta_over_e (de/dt)^2.
double state_based_damping_power(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                                 const double* vel, double eta_over_e);

// A stable step of explicit integration, min over particles: the energy is bounded by that of
// pair bonds of stiffness k = 2 w beta |xi| V^2 (A_i / m_i + A_j / m_j), A_i = max(2 kappa, 4 mu_i) (the
// bulk part by Cauchy-Schwarz, theta^2 <= (4 / m) sum w beta e^2 V), whose Silling & Askari bound
// sqrt(2 m_i / sum_j k / |xi|) then holds for the LPS as well.
double state_based_critical_time_step(const BondStore& bonds, const BondState& live, const LpsFields& lps,
                                      const std::vector<double>& masses);

}  // namespace periflex
