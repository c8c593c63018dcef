// The state-based row loops eight bonds at a time with AVX-512 (see state_based_rows.h).
#include <immintrin.h>

#include <algorithm>

#include "pd/state_based_rows.h"

#ifdef PERIFLEX_HAVE_LPS_AVX512

namespace periflex {

namespace {

#define PERIFLEX_LPS_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq")))

// 1/|y| from the hardware estimate (relative error under 2^-14) refined by two Newton steps,
// which leave it at round-off; no division or square root unit involved.
PERIFLEX_LPS_AVX512 inline __m512d reciprocal_length(__m512d r2) {
  const __m512d half = _mm512_set1_pd(0.5), one = _mm512_set1_pd(1.0);
  __m512d y = _mm512_rsqrt14_pd(r2);
  for (int step = 0; step < 2; ++step) {
    const __m512d residual = _mm512_fnmadd_pd(_mm512_mul_pd(r2, y), y, one);  // 1 - r2 y^2
    y = _mm512_fmadd_pd(_mm512_mul_pd(half, y), residual, y);
  }
  return y;
}

// |xi| and 1/|xi| per length class, each table in two registers (classes 0-7 and 8-15)
struct ClassTables {
  __m512d length_lo, length_hi, inv_lo, inv_hi;
};

PERIFLEX_LPS_AVX512 inline ClassTables class_tables(const BondStore& bonds) {
  alignas(64) double length[16] = {}, inv[16] = {};
  const int classes = std::min<int>(static_cast<int>(bonds.inv_length_table.size()), 16);
  for (int c = 1; c < classes; ++c) {
    inv[c] = bonds.inv_length_table[c];
    length[c] = inv[c] > 0.0 ? 1.0 / inv[c] : 0.0;
  }
  return {_mm512_load_pd(length), _mm512_load_pd(length + 8), _mm512_load_pd(inv), _mm512_load_pd(inv + 8)};
}

// One block of up to eight bonds [b, min(b + 8, last)): masked-off lanes point at the particle
// itself with w = 0 and class 0, so they add nothing.
struct Block {
  __mmask8 mask;
  __m256i twice_j;  // 2 j, the x coordinate of the neighbour
  __m512i cls;      // length class
  __m512d w;        // bond weight, 0 once broken or masked
};

// kOffsets: neighbours read as 16-bit offsets j - i, half the bytes of the 32-bit indices (the
// loops stream the bond arrays twice a step, so the bytes count)
template <bool kOffsets>
PERIFLEX_LPS_AVX512 inline Block load_block(const BondStore& bonds, int64_t b, int64_t last, int i) {
  Block k;
  const int64_t left = last - b;
  k.mask = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
  __m256i j;
  if constexpr (kOffsets)
    j = _mm256_add_epi32(_mm256_cvtepi16_epi32(_mm_maskz_loadu_epi16(k.mask, bonds.neighbor_offset.data() + b)),
                         _mm256_set1_epi32(i));
  else
    j = _mm256_mask_loadu_epi32(_mm256_set1_epi32(i), k.mask, bonds.neighbor.data() + b);
  k.twice_j = _mm256_slli_epi32(j, 1);
  k.cls = _mm512_cvtepu8_epi64(_mm_maskz_loadu_epi8(__mmask16(k.mask), bonds.length_class.data() + b));
  k.w = _mm512_cvtps_pd(_mm256_maskz_loadu_ps(k.mask, bonds.stiffness.data() + b));
  return k;
}

template <bool kTrack, bool kOffsets>
PERIFLEX_LPS_AVX512 void extension_sums(int begin, int end, const BondStore& bonds, const double* __restrict pos,
                                        double* __restrict sum, double* __restrict most) {
  const ClassTables t = class_tables(bonds);
  const __m512d one = _mm512_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d acc = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    const int64_t last = bonds.row[i + 1];
    for (int64_t b = bonds.row[i]; b < last; b += 8) {
      const Block k = load_block<kOffsets>(bonds, b, last, i);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(k.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(k.twice_j, pos + 1, 8), yi);
      const __m512d r2 = _mm512_mask_blend_pd(k.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d len = _mm512_mul_pd(r2, reciprocal_length(r2));
      const __m512d x0 = _mm512_permutex2var_pd(t.length_lo, k.cls, t.length_hi);
      // w |xi| (|y| - |xi|)
      acc = _mm512_fmadd_pd(_mm512_mul_pd(k.w, x0), _mm512_sub_pd(len, x0), acc);
      if constexpr (kTrack) {
        const __m512d inv0 = _mm512_permutex2var_pd(t.inv_lo, k.cls, t.inv_hi);
        const __m512d s = _mm512_fmsub_pd(len, inv0, one);
        top = _mm512_mask_max_pd(top, _mm512_cmp_pd_mask(k.w, _mm512_setzero_pd(), _CMP_GT_OQ), top, s);
      }
    }
    sum[i] = _mm512_reduce_add_pd(acc);
    if constexpr (kTrack) most[i] = _mm512_reduce_max_pd(top);
  }
}

}  // namespace

PERIFLEX_LPS_AVX512 void lps_extension_sums_avx512(int begin, int end, const BondStore& bonds, const double* pos,
                                                   double* sum, double* most) {
  const bool offsets = !bonds.neighbor_offset.empty();
  if (most && offsets)
    extension_sums<true, true>(begin, end, bonds, pos, sum, most);
  else if (most)
    extension_sums<true, false>(begin, end, bonds, pos, sum, most);
  else if (offsets)
    extension_sums<false, true>(begin, end, bonds, pos, sum, most);
  else
    extension_sums<false, false>(begin, end, bonds, pos, sum, most);
}

namespace {

template <bool kOffsets>
PERIFLEX_LPS_AVX512 void forces(int begin, int end, const BondStore& bonds, const double* __restrict ab, double v2,
                                const double* __restrict pos, double* __restrict force) {
  const ClassTables t = class_tables(bonds);
  const __m512d one = _mm512_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    const __m512d ai = _mm512_set1_pd(ab[2 * i]), bi = _mm512_set1_pd(ab[2 * i + 1]);
    __m512d fx = _mm512_setzero_pd(), fy = _mm512_setzero_pd();
    const int64_t last = bonds.row[i + 1];
    for (int64_t b = bonds.row[i]; b < last; b += 8) {
      const Block k = load_block<kOffsets>(bonds, b, last, i);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(k.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(k.twice_j, pos + 1, 8), yi);
      const __m512d r2 = _mm512_mask_blend_pd(k.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d inv_len = reciprocal_length(r2);
      const __m512d len = _mm512_mul_pd(r2, inv_len);
      const __m512d x0 = _mm512_permutex2var_pd(t.length_lo, k.cls, t.length_hi);
      // a_j and b_j side by side, as x_j and y_j are: the same index, one cache line
      const __m512d aj = _mm512_add_pd(ai, _mm512_i32gather_pd(k.twice_j, ab, 8));
      const __m512d bj = _mm512_add_pd(bi, _mm512_i32gather_pd(k.twice_j, ab + 1, 8));
      // w ((a_i + a_j) |xi| + (b_i + b_j) (|y| - |xi|)) / |y|
      const __m512d pair = _mm512_fmadd_pd(aj, x0, _mm512_mul_pd(bj, _mm512_sub_pd(len, x0)));
      const __m512d f = _mm512_mul_pd(_mm512_mul_pd(k.w, pair), inv_len);
      fx = _mm512_fmadd_pd(f, dx, fx);
      fy = _mm512_fmadd_pd(f, dy, fy);
    }
    force[2 * i] += v2 * _mm512_reduce_add_pd(fx);
    force[2 * i + 1] += v2 * _mm512_reduce_add_pd(fy);
  }
}

}  // namespace

PERIFLEX_LPS_AVX512 void lps_forces_avx512(int begin, int end, const BondStore& bonds, const double* ab, double v2,
                                           const double* pos, double* force) {
  if (!bonds.neighbor_offset.empty())
    forces<true>(begin, end, bonds, ab, v2, pos, force);
  else
    forces<false>(begin, end, bonds, ab, v2, pos, force);
}

}  // namespace periflex

#endif
