// Internal to the state-based loops (state_based_kernel.cpp): the two undamped row loops written
// for AVX-512, eight bonds a vector, used when the CPU has it and the body has at most 16 bond
// length classes (horizons up to about 3.9 grid spacings). Same formulas as the loops in
// state_based_kernel.cpp, to round-off.
#pragma once

#include <cstdint>

#include "pd/bond_state.h"
#include "pd/bond_store.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PERIFLEX_HAVE_LPS_AVX512 1
#endif

namespace periflex {

#ifdef PERIFLEX_HAVE_LPS_AVX512
// sum[i] = sum_j w |xi| (|y| - |xi|) over row i, i in [begin, end); with most non-null, the largest
// stretch over the row's intact bonds (-1 without any) to most[i].
void lps_extension_sums_avx512(int begin, int end, const BondStore& bonds, const BondState& live, const double* pos,
                               double* sum, double* most);
// force_i += v2 sum_j w ((a_i + a_j) |xi| + (b_i + b_j) (|y| - |xi|)) y / |y|, with the records
// [x_0 y_0 a_0 b_0 x_1 ...] (positions and coefficients of each particle in 32 bytes: a neighbour is
// one load, not four gathered elements).
void lps_forces_avx512(int begin, int end, const BondStore& bonds, const BondState& live, const double* records,
                       double v2, double* force);
#endif

}  // namespace periflex
