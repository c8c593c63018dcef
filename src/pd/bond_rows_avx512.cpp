// The bond row loops eight bonds at a time with AVX-512 (see bond_rows.h).
#include <immintrin.h>

#include <algorithm>
#include <type_traits>

#include "pd/bond_rows.h"

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS

namespace periflex {

namespace {

// ---- AVX-512: eight bonds a vector, no division and no square root ----
// vdivpd and vsqrtpd share one unit and bounded the AVX2 loops. 1/|y| starts from the hardware
// estimate (relative error under 2^-14) and two Newton steps, each squaring the error, take it
// to round-off. 1/|xi| comes from the class table held in two registers (a permute) when the
// body has at most 16 length classes (horizons up to about 3.9 grid spacings), else from a
// gather. The row's last (length mod 8) bonds run in the same loop under a lane mask: masked
// lanes see the particle itself with k = 0 and add nothing.

#define PERIFLEX_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))

PERIFLEX_AVX512 inline __m512d inverse_length(__m512d r2) {
  const __m512d half = _mm512_set1_pd(0.5), one = _mm512_set1_pd(1.0);
  __m512d y = _mm512_rsqrt14_pd(r2);
  for (int step = 0; step < 2; ++step) {
    // y += y (1 - r2 y^2) / 2, the correction formed with fused operations
    const __m512d e = _mm512_fnmadd_pd(_mm512_mul_pd(r2, y), y, one);
    y = _mm512_fmadd_pd(_mm512_mul_pd(half, y), e, y);
  }
  return y;
}

// The lanes of one block of up to eight bonds [b, min(b + 8, last)) of row i.
struct Lanes {
  __mmask8 mask;
  __m256i twice_j;  // 2 j: x of the neighbour in the interleaved positions
  __m512d l0;       // 1 / |xi|
  __m512d k;        // stiffness, 0 in masked lanes
};

// kSmallTable: the class table fits the two registers table_lo (classes 0-7) and table_hi (8-15).
// kOffsets: neighbours read as 16-bit offsets j - i (r.off), half the bytes of the indices.
template <bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 inline Lanes load_lanes(const Rows& r, int64_t b, int64_t last, int i, __m512d table_lo,
                                        __m512d table_hi) {
  Lanes l;
  const int64_t left = last - b;
  l.mask = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
  __m256i j;
  if constexpr (kOffsets)
    j = _mm256_add_epi32(_mm256_cvtepi16_epi32(_mm_maskz_loadu_epi16(l.mask, r.off + b)), _mm256_set1_epi32(i));
  else
    j = _mm256_mask_loadu_epi32(_mm256_set1_epi32(i), l.mask, r.nbr + b);
  l.twice_j = _mm256_slli_epi32(j, 1);
  // masked lanes read class 0, whose table entry is 0
  const __m512i cls = _mm512_cvtepu8_epi64(_mm_maskz_loadu_epi8(__mmask16(l.mask), r.cls + b));
  if constexpr (kSmallTable)
    l.l0 = _mm512_permutex2var_pd(table_lo, cls, table_hi);
  else
    l.l0 = _mm512_i64gather_pd(cls, r.l0, 8);
  l.k = _mm512_cvtps_pd(_mm256_maskz_loadu_ps(l.mask, r.k + b));
  return l;
}

// the class table in two registers (unused entries 0)
PERIFLEX_AVX512 inline void table_registers(const Rows& r, __m512d& lo, __m512d& hi) {
  alignas(64) double t[16] = {};
  for (int c = 0; c < std::min(r.classes, 16); ++c) t[c] = r.l0[c];
  lo = _mm512_load_pd(t);
  hi = _mm512_load_pd(t + 8);
}

// stretch of the intact lanes (k > 0) folded into the running maximum
PERIFLEX_AVX512 inline __m512d track_max(__m512d top, __m512d r2, __m512d inv_len, const Lanes& l) {
  const __m512d s = _mm512_fmsub_pd(_mm512_mul_pd(r2, inv_len), l.l0, _mm512_set1_pd(1.0));
  return _mm512_mask_max_pd(top, _mm512_cmp_pd_mask(l.k, _mm512_setzero_pd(), _CMP_GT_OQ), top, s);
}

template <bool kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void elastic_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                         double* __restrict force, double* __restrict most, const RowCut* cut) {
  const __m512d one = _mm512_set1_pd(1.0);
  __m512d table_lo, table_hi;
  table_registers(r, table_lo, table_hi);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d ax = _mm512_setzero_pd(), ay = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    const int64_t last = r.row[i + 1];
    for (int64_t b = r.row[i]; b < last; b += 8) {
      const Lanes l = load_lanes<kSmallTable, kOffsets>(r, b, last, i, table_lo, table_hi);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos + 1, 8), yi);
      // masked lanes hold the particle itself (r2 = 0): give them r2 = 1 so nothing is infinite
      const __m512d r2 = _mm512_mask_blend_pd(l.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d inv_len = inverse_length(r2);
      const __m512d f = _mm512_mul_pd(l.k, _mm512_sub_pd(l.l0, inv_len));
      ax = _mm512_fmadd_pd(f, dx, ax);
      ay = _mm512_fmadd_pd(f, dy, ay);
      if constexpr (kTrack) top = track_max(top, r2, inv_len, l);
    }
    if constexpr (kTrack) {
      const double largest = _mm512_reduce_max_pd(top);
      if (most) most[i] = largest;
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (cut && largest > cut->s0 - kCutSlack) {
        double fx = 0.0, fy = 0.0;
        cut_row_forces(i, r, *cut, pos, nullptr, 0.0, fx, fy);
        force[2 * i] += fx;
        force[2 * i + 1] += fy;
        continue;
      }
    }
    force[2 * i] += _mm512_reduce_add_pd(ax);
    force[2 * i + 1] += _mm512_reduce_add_pd(ay);
  }
}

template <bool kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void damped_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                        const double* __restrict vel, double eta_over_e, double* __restrict force,
                                        double* __restrict most, const RowCut* cut) {
  const __m512d one = _mm512_set1_pd(1.0), eta = _mm512_set1_pd(eta_over_e);
  __m512d table_lo, table_hi;
  table_registers(r, table_lo, table_hi);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    const __m512d vxi = _mm512_set1_pd(vel[2 * i]), vyi = _mm512_set1_pd(vel[2 * i + 1]);
    __m512d ax = _mm512_setzero_pd(), ay = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    const int64_t last = r.row[i + 1];
    for (int64_t b = r.row[i]; b < last; b += 8) {
      const Lanes l = load_lanes<kSmallTable, kOffsets>(r, b, last, i, table_lo, table_hi);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos + 1, 8), yi);
      const __m512d dvx = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, vel, 8), vxi);
      const __m512d dvy = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, vel + 1, 8), vyi);
      const __m512d r2 = _mm512_mask_blend_pd(l.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d inv_len = inverse_length(r2);
      // k (s + eta/E ds/dt) / |y| with ds/dt = (y . dv) / (|y| |xi|)
      const __m512d dot = _mm512_fmadd_pd(dx, dvx, _mm512_mul_pd(dy, dvy));
      const __m512d rate = _mm512_mul_pd(_mm512_mul_pd(dot, inv_len), l.l0);
      const __m512d f =
          _mm512_mul_pd(l.k, _mm512_fmadd_pd(_mm512_mul_pd(eta, rate), inv_len, _mm512_sub_pd(l.l0, inv_len)));
      ax = _mm512_fmadd_pd(f, dx, ax);
      ay = _mm512_fmadd_pd(f, dy, ay);
      if constexpr (kTrack) top = track_max(top, r2, inv_len, l);
    }
    if constexpr (kTrack) {
      const double largest = _mm512_reduce_max_pd(top);
      if (most) most[i] = largest;
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (cut && largest > cut->s0 - kCutSlack) {
        double fx = 0.0, fy = 0.0;
        cut_row_forces(i, r, *cut, pos, vel, eta_over_e, fx, fy);
        force[2 * i] += fx;
        force[2 * i + 1] += fy;
        continue;
      }
    }
    force[2 * i] += _mm512_reduce_add_pd(ax);
    force[2 * i + 1] += _mm512_reduce_add_pd(ay);
  }
}

template <bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void row_max_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                            double* __restrict out) {
  const __m512d one = _mm512_set1_pd(1.0);
  __m512d table_lo, table_hi;
  table_registers(r, table_lo, table_hi);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d top = _mm512_set1_pd(-1.0);
    const int64_t last = r.row[i + 1];
    for (int64_t b = r.row[i]; b < last; b += 8) {
      const Lanes l = load_lanes<kSmallTable, kOffsets>(r, b, last, i, table_lo, table_hi);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos + 1, 8), yi);
      const __m512d r2 = _mm512_mask_blend_pd(l.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      top = track_max(top, r2, inverse_length(r2), l);
    }
    out[i] = _mm512_reduce_max_pd(top);
  }
}

// site picks among the eight compiled variants of an AVX-512 row loop.
template <typename Fn>
void with_avx512_options(const Rows& r, bool track, Fn&& fn) {
  auto by_offsets = [&](auto t, auto small) {
    if (r.off)
      fn(t, small, std::true_type{});
    else
      fn(t, small, std::false_type{});
  };
  auto by_table = [&](auto t) {
    if (r.classes <= 16)
      by_offsets(t, std::true_type{});
    else
      by_offsets(t, std::false_type{});
  };
  if (track)
    by_table(std::true_type{});
  else
    by_table(std::false_type{});
}

}  // namespace

void elastic_rows_avx512(int begin, int end, const Rows& r, const double* pos, double* force, double* most,
                         const RowCut* cut) {
  with_avx512_options(r, most || cut, [&](auto track, auto small, auto offsets) {
    elastic_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, force, most, cut);
  });
}

void damped_rows_avx512(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                        double* force, double* most, const RowCut* cut) {
  with_avx512_options(r, most || cut, [&](auto track, auto small, auto offsets) {
    damped_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, vel, eta_over_e, force, most, cut);
  });
}

void row_max_stretch_avx512(int begin, int end, const Rows& r, const double* pos, double* out) {
  with_avx512_options(r, false, [&](auto, auto small, auto offsets) {
    row_max_avx512<small.value, offsets.value>(begin, end, r, pos, out);
  });
}

}  // namespace periflex

#endif
