// Internal to the bond loops (bond_kernel.cpp and the vector files beside it): what a row loop
// reads, and the AVX2 and AVX-512 row loops, each in a file of its own, chosen at run time.
#pragma once

#include <cstdint>

#include "pd/bond_state.h"
#include "pd/bond_store.h"

// On x86-64 with GCC or Clang the row loops also exist as AVX-512 code (eight bonds a vector)
// and AVX2 code (four), chosen at run time by what the CPU has.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PERIFLEX_HAVE_VECTOR_KERNELS 1
#endif

namespace periflex {

// What the row loops read, as plain pointers.
struct Rows {
  const int64_t* row;
  const int32_t* nbr;
  const int16_t* off;    // j - i of each bond, or null (see BondStore::neighbor_offset)
  const uint8_t* cls;    // length class of each bond
  const double* l0;      // 1 / |xi| per length class
  int classes;           // entries of l0
  const float* k;        // stiffness, 0 once broken (BondState::stiffness)
  const double* own;     // 1 / |xi| of each bond of a body off the grid (BondStore::bond_inv_length), or null
  const double* ps0;     // critical stretch of each particle (materials by block), or null: RowCut::s0
  const double* rs0;     // each row's smallest bond threshold (BondStore::row_s0), or null
};

// 1 / |xi| of bond b
inline double ref_inv_length(const Rows& r, int64_t b) { return r.own ? r.own[b] : r.l0[r.cls[b]]; }

inline Rows rows_of(const BondStore& b, const BondState& live) {
  return {b.row.data(), b.neighbor.data(), b.neighbor_offset.empty() ? nullptr : b.neighbor_offset.data(),
          b.length_class.data(), b.inv_length_table.data(),
          static_cast<int>(b.inv_length_table.size()), live.stiffness.data(),
          b.own_lengths() ? b.bond_inv_length.data() : nullptr,
          b.own_break_stretches() ? b.particle_s0.data() : nullptr,
          b.own_break_stretches() ? b.row_s0.data() : nullptr};
}

// Bonds past the critical stretch inside a force loop. A row whose largest intact stretch (as the
// vector loop computes it) comes within kCutSlack of s0 is summed again by cut_row_forces, which
// takes the exact stretch of each bond (the same bits for both copies) and leaves out every
// breakable bond past s0.
struct RowCut {
  double s0;
  const uint8_t* no_fail;  // 1: bonds at this particle never break; may be null
  uint8_t* broken;         // a bond left out is marked 2 (broken, not yet settled)
  uint8_t* row_broke;      // set to 1 for a row that left a bond out
};

// The stretch below which no bond of row i breaks, and the one past which bond b (to j) does.
inline double row_threshold(const Rows& r, const RowCut& cut, int i) { return r.rs0 ? r.rs0[i] : cut.s0; }
inline double bond_threshold(const Rows& r, const RowCut& cut, int i, int32_t j) {
  return r.ps0 ? (r.ps0[i] < r.ps0[j] ? r.ps0[i] : r.ps0[j]) : cut.s0;
}

// The row maxima of the vector loops may differ from the exact stretch by a few units in the
// last place (their 1/|y| is a refined estimate); rows within this much of s0 are walked exactly.
constexpr double kCutSlack = 1e-12;

// Forces of row i (added to fx, fy, which start at 0) without its breakable intact bonds past s0,
// in the portable formulas; vel null: elastic only. Defined in bond_kernel.cpp.
void cut_row_forces(int i, const Rows& r, const RowCut& cut, const double* pos, const double* vel,
                    double eta_over_e, double& fx, double& fy);

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
// Rows [begin, end): forces added to force; with most non-null, each row's largest stretch over
// its intact bonds (-1 without any) written to most[i]; with cut non-null (and most null: a
// breaking evaluation leaves no maxima), rows near or past s0 summed by cut_row_forces. Same formulas as the portable loops in bond_kernel.cpp, to round-off.
void elastic_rows_avx2(int begin, int end, const Rows& r, const double* pos, double* force, double* most,
                       const RowCut* cut);
void damped_rows_avx2(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                      double* force, double* most, const RowCut* cut);
void elastic_rows_avx512(int begin, int end, const Rows& r, const double* pos, double* force, double* most,
                         const RowCut* cut);
void damped_rows_avx512(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                        double* force, double* most, const RowCut* cut);
// Strain energy of rows [begin, end) into sum (a quarter of k |xi| s^2 per stored direction, row
// by row in order); false (sum untouched) when the class table does not fit two registers.
bool strain_energy_avx512(int begin, int end, const Rows& r, const double* pos, double& sum);
// Each row's largest stretch over its intact bonds (-1 without any).
void row_max_stretch_avx512(int begin, int end, const Rows& r, const double* pos, double* out);
#endif

}  // namespace periflex
