// The hot loops over the bonds of one body. Positions and velocities are interleaved
// [x0 y0 x1 y1 ...] (the body's slice of q and qd); forces are added to an interleaved array.
// Each particle sums its own row, so the result does not depend on the thread count.
#pragma once

#include <cstdint>

#include "pd/bond_store.h"

namespace periflex {

// force_i += sum_j k s e_ij with s = |y_j - y_i| / |xi| - 1 (elastic bond forces). When
// row_max is given it receives, per particle, the largest stretch over its intact bonds
// (at most 0 when it has none) as a by-product, which break_stretched_bonds can reuse at the same positions.
// pos_copy, when given, receives a copy of pos (2 per particle), made chunk by chunk inside the
// parallel loop rather than in a pass of its own.
void add_bond_forces(const BondStore& bonds, const double* pos, double* force,
                     double* row_max = nullptr, double* pos_copy = nullptr);

// As add_bond_forces plus viscous bond damping: pair force k (s + eta_over_e * ds/dt).
void add_damped_bond_forces(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e,
                            double* force, double* row_max = nullptr, double* pos_copy = nullptr);

// Strain energy sum over pairs of k |xi| s^2 / 2.
double bond_strain_energy(const BondStore& bonds, const double* pos);

// Power the bond damping removes: sum over pairs of k eta_over_e |xi| (ds/dt)^2.
double bond_damping_power(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e);

// Breaks every intact bond with s > s0 unless an end is flagged in no_fail (may be null).
// Returns the number of pairs broken; energy_released gets the strain energy they held.
// row_max, when given, must come from a force evaluation at exactly these positions.
long break_stretched_bonds(BondStore& bonds, const double* pos, double s0, const uint8_t* no_fail,
                           double& energy_released, const double* row_max = nullptr);

// The widest row loops that may run when the CPU has them (default kAvx512). The loops agree
// to round-off; narrower ones are for tests and comparisons.
enum class VectorKernels { kPortable, kAvx2, kAvx512 };
void set_vector_kernels(VectorKernels widest);
// set_vector_kernels(enabled ? kAvx512 : kPortable).
void set_vector_kernels_enabled(bool enabled);

// Largest stretch over the intact bonds of each particle (0 without intact bonds).
void max_bond_stretch(const BondStore& bonds, const double* pos, float* out);

}  // namespace periflex
