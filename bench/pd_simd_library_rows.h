// The elastic bond row loop written once with xsimd (libxsimd-dev) and compiled for AVX-512 and for
// AVX2 (pd_simd_library_rows.cpp, built twice with different flags), to compare one library source
// against the hand-written loops of src/pd (bench/pd_simd_library_bench.cpp).
#pragma once

#include <cstdint>

namespace periflex::bench {

// The arrays a row loop reads (as pd::Rows): rows [begin, end) add their elastic bond forces
// sum_j k (1/|xi| - 1/|y|) y to force.
struct RowArrays {
  const int64_t* row;
  const int32_t* nbr;
  const uint8_t* cls;
  const double* l0;  // 1/|xi| per length class
  const float* k;    // stiffness, 0 once broken
};

void elastic_rows_xsimd_avx512(int begin, int end, const RowArrays& r, const double* pos, double* force);
void elastic_rows_xsimd_avx2(int begin, int end, const RowArrays& r, const double* pos, double* force);
// the same loop with the neighbours' coordinates gathered by the library (batch::gather)
void elastic_rows_xsimd_gather_avx512(int begin, int end, const RowArrays& r, const double* pos, double* force);
void elastic_rows_xsimd_gather_avx2(int begin, int end, const RowArrays& r, const double* pos, double* force);

}  // namespace periflex::bench
