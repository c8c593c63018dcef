// Internal to the bond loops (bond_kernel.cpp and the vector files beside it): what a row loop
// reads, and the AVX2 and AVX-512 row loops, each in a file of its own, chosen at run time.
#pragma once

#include <cstdint>

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
  const float* k;        // stiffness, 0 once broken
};

inline Rows rows_of(const BondStore& b) {
  return {b.row.data(), b.neighbor.data(), b.neighbor_offset.empty() ? nullptr : b.neighbor_offset.data(),
          b.length_class.data(), b.inv_length_table.data(),
          static_cast<int>(b.inv_length_table.size()), b.stiffness.data()};
}

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
// Rows [begin, end): forces added to force; with most non-null, each row's largest stretch over
// its intact bonds (-1 without any) written to most[i]. Same formulas as the portable loops in
// bond_kernel.cpp, to round-off.
void elastic_rows_avx2(int begin, int end, const Rows& r, const double* pos, double* force, double* most);
void damped_rows_avx2(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                      double* force, double* most);
void elastic_rows_avx512(int begin, int end, const Rows& r, const double* pos, double* force, double* most);
void damped_rows_avx512(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                        double* force, double* most);
// Each row's largest stretch over its intact bonds (-1 without any).
void row_max_stretch_avx512(int begin, int end, const Rows& r, const double* pos, double* out);
#endif

}  // namespace periflex
