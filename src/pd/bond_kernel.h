// The hot loops over the bonds of one body. Positions and velocities are interleaved
// [x0 y0 x1 y1 ...] (the body's slice of q and qd); forces are added to an interleaved array.
// Each particle sums its own row, so the result does not depend on the thread count.
#pragma once

#include <cstdint>

#include "pd/bond_state.h"
#include "pd/bond_store.h"

namespace periflex {

// force_i += sum_j k s e_ij with s = |y_j - y_i| / |xi| - 1 (elastic bond forces). When
// row_max is given it receives, per particle, the largest stretch over its intact bonds
// (at most 0 when it has none) as a by-product, which break_stretched_bonds can reuse at the same positions.
// pos_copy, when given, receives a copy of pos (2 per particle), made chunk by chunk inside the
// parallel loop rather than in a pass of its own.
void add_bond_forces(const BondStore& bonds, const BondState& live, const double* pos, double* force,
                     double* row_max = nullptr, double* pos_copy = nullptr);

// As add_bond_forces plus viscous bond damping: pair force k (s + eta_over_e * ds/dt).
void add_damped_bond_forces(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                            double eta_over_e, double* force, double* row_max = nullptr, double* pos_copy = nullptr);

// A force evaluation that breaks bonds (add_bond_forces_breaking).
struct BreakingEvaluation {
  double s0 = 0.0;                 // critical stretch
  const uint8_t* no_fail = nullptr;  // 1: bonds at this particle never break; may be null
  // one flag per particle, all 0 on entry: set for a row whose bonds broke (both copies of each
  // are marked broken = 2 for settle_broken_bonds)
  uint8_t* row_broke = nullptr;
};

// As add_damped_bond_forces (vel non-null, eta_over_e > 0) or add_bond_forces, except that every
// intact bond whose exact stretch exceeds s0 (and no end of which is in no_fail) contributes no
// force: a bond breaks in the evaluation that first sees it past s0. Both copies see the same
// stretch bit for bit and decide alike, on any thread count.
void add_bond_forces_breaking(const BondStore& bonds, BondState& live, const double* pos, const double* vel,
                              double eta_over_e, const BreakingEvaluation& breaking, double* force,
                              double* pos_copy = nullptr);

// Completes the breaks an evaluation at pos (and vel) marked: k = 0, broken = 1, flags
// cleared. Returns the pairs broken; energy_released gets the strain energy they held at pos less,
// when half_kick > 0, the work their forces would have done over a half-kick of that length
// after the evaluation (velocity Verlet's, which the bonds no longer take part in).
long settle_broken_bonds(const BondStore& bonds, BondState& live, const double* pos, const double* vel,
                         double half_kick, uint8_t* row_broke, double& energy_released);

// Strain energy sum over pairs of k |xi| s^2 / 2.
double bond_strain_energy(const BondStore& bonds, const BondState& live, const double* pos);

// Power the bond damping removes: sum over pairs of k eta_over_e |xi| (ds/dt)^2.
double bond_damping_power(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                          double eta_over_e);

// Breaks every intact bond with s > s0 unless an end is flagged in no_fail (may be null).
// Returns the number of pairs broken; energy_released gets the strain energy they held.
// row_max, when given, must come from a force evaluation at exactly these positions.
long break_stretched_bonds(const BondStore& bonds, BondState& live, const double* pos, double s0,
                           const uint8_t* no_fail, double& energy_released, const double* row_max = nullptr);

// The widest row loops that may run when the CPU has them (default kAvx512). The loops agree
// to round-off; narrower ones are for tests and comparisons.
enum class VectorKernels { kPortable, kAvx2, kAvx512 };
void set_vector_kernels(VectorKernels widest);
// set_vector_kernels(enabled ? kAvx512 : kPortable).
void set_vector_kernels_enabled(bool enabled);

// Largest stretch over the intact bonds of each particle (0 without intact bonds).
void max_bond_stretch(const BondStore& bonds, const BondState& live, const double* pos, float* out);

}  // namespace periflex
