// The bond row loops eight bonds at a time with AVX-512 (see bond_rows.h).
#include <immintrin.h>

#include <algorithm>
#include <type_traits>

#include "pd/bond_prefetch.h"
#include "pd/bond_rows.h"

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS

namespace periflex {

namespace {

// the bond arrays some rows past bond b, fetched ahead of the loop (bond_prefetch.h)
template <bool kOffsets>
inline void prefetch_rows_ahead(const Rows& r, int64_t b) {
  if constexpr (kOffsets)
    prefetch_bonds_ahead(r.k, r.cls, r.off, b);
  else
    prefetch_bonds_ahead(r.k, r.cls, r.nbr, b);
}

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

// What a force loop tracks besides the forces: nothing, each row's largest intact stretch, or
// only whether some intact bond of the row comes near s0 (the cheaper test of a breaking
// evaluation: r2 / |xi|^2 against (1 + s0 - slack)^2, no reduction per row).
enum Track { kNothing, kLargest, kNear };

// lanes of intact bonds (k > 0) whose squared length ratio exceeds limit2
PERIFLEX_AVX512 inline __mmask8 near_lanes(__m512d r2, const Lanes& l, __m512d limit2) {
  const __mmask8 intact = _mm512_cmp_pd_mask(l.k, _mm512_setzero_pd(), _CMP_GT_OQ);
  return _mm512_mask_cmp_pd_mask(intact, _mm512_mul_pd(r2, _mm512_mul_pd(l.l0, l.l0)), limit2, _CMP_GT_OQ);
}

// (1 + s0 - slack)^2 of a breaking evaluation (infinite without one)
inline double near_limit(const RowCut* cut) {
  if (!cut) return __builtin_inf();
  const double ratio = 1.0 + cut->s0 - kCutSlack;
  return ratio * ratio;
}

// x and y of the neighbours of the eight lanes of block b (the particle itself past the row's
// end, as in load_lanes) from one 16-byte load each and a deinterleave in registers: cheaper than
// two gathers of eight, which each cost eight loads and a long microcode sequence.
// [x y] of four particles j[0..3] side by side (16-byte lanes moved as four floats: AVX-512F only)
PERIFLEX_AVX512 inline __m512d four_points(const double* pos, const int* j) {
  auto point = [pos](int k) { return _mm_castpd_ps(_mm_loadu_pd(pos + 2 * static_cast<int64_t>(k))); };
  __m512 z = _mm512_castps128_ps512(point(j[0]));
  z = _mm512_insertf32x4(z, point(j[1]), 1);
  z = _mm512_insertf32x4(z, point(j[2]), 2);
  z = _mm512_insertf32x4(z, point(j[3]), 3);
  return _mm512_castps_pd(z);
}

template <bool kOffsets>
PERIFLEX_AVX512 inline void load_points(const Rows& r, const double* pos, int64_t b, int64_t left, int i, __m512d& x,
                                        __m512d& y) {
  int j[8];
  for (int k = 0; k < 8; ++k) j[k] = k >= left ? i : (kOffsets ? i + r.off[b + k] : r.nbr[b + k]);
  // [x0 y0 ... x3 y3] and [x4 y4 ... x7 y7] -> [x0 ... x7], [y0 ... y7]
  const __m512d lo = four_points(pos, j), hi = four_points(pos, j + 4);
  x = _mm512_permutex2var_pd(lo, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), hi);
  y = _mm512_permutex2var_pd(lo, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), hi);
}

template <Track kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void elastic_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                         double* __restrict force, double* __restrict most, const RowCut* cut) {
  const __m512d one = _mm512_set1_pd(1.0), limit2 = _mm512_set1_pd(near_limit(cut));
  __m512d table_lo, table_hi;
  table_registers(r, table_lo, table_hi);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d ax = _mm512_setzero_pd(), ay = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    __mmask8 near = 0;
    const int64_t last = r.row[i + 1];
    prefetch_rows_ahead<kOffsets>(r, last);
    for (int64_t b = r.row[i]; b < last; b += 8) {
      const Lanes l = load_lanes<kSmallTable, kOffsets>(r, b, last, i, table_lo, table_hi);
      __m512d xj, yj;
      load_points<kOffsets>(r, pos, b, last - b, i, xj, yj);
      const __m512d dx = _mm512_sub_pd(xj, xi), dy = _mm512_sub_pd(yj, yi);
      // masked lanes hold the particle itself (r2 = 0): give them r2 = 1 so nothing is infinite
      const __m512d r2 = _mm512_mask_blend_pd(l.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d inv_len = inverse_length(r2);
      const __m512d f = _mm512_mul_pd(l.k, _mm512_sub_pd(l.l0, inv_len));
      ax = _mm512_fmadd_pd(f, dx, ax);
      ay = _mm512_fmadd_pd(f, dy, ay);
      if constexpr (kTrack == kLargest) top = track_max(top, r2, inv_len, l);
      if constexpr (kTrack == kNear) near |= near_lanes(r2, l, limit2);
    }
    if constexpr (kTrack == kLargest) most[i] = _mm512_reduce_max_pd(top);
    if constexpr (kTrack == kNear) {
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (near) {
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

template <Track kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void damped_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                        const double* __restrict vel, double eta_over_e, double* __restrict force,
                                        double* __restrict most, const RowCut* cut) {
  const __m512d one = _mm512_set1_pd(1.0), eta = _mm512_set1_pd(eta_over_e);
  const __m512d limit2 = _mm512_set1_pd(near_limit(cut));
  __m512d table_lo, table_hi;
  table_registers(r, table_lo, table_hi);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    const __m512d vxi = _mm512_set1_pd(vel[2 * i]), vyi = _mm512_set1_pd(vel[2 * i + 1]);
    __m512d ax = _mm512_setzero_pd(), ay = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    __mmask8 near = 0;
    const int64_t last = r.row[i + 1];
    prefetch_rows_ahead<kOffsets>(r, last);
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
      if constexpr (kTrack == kLargest) top = track_max(top, r2, inv_len, l);
      if constexpr (kTrack == kNear) near |= near_lanes(r2, l, limit2);
    }
    if constexpr (kTrack == kLargest) most[i] = _mm512_reduce_max_pd(top);
    if constexpr (kTrack == kNear) {
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (near) {
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
    prefetch_rows_ahead<kOffsets>(r, last);
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

// Sum over rows [begin, end) of a quarter of each row's sum of k |xi| s^2 (the strain energy,
// each pair visited from both ends), rows added in order. |xi| = 1 / l0 from a second class
// table; the stretch from the refined 1/|y|, as in the force loops.
template <bool kOffsets>
PERIFLEX_AVX512 double energy_avx512(int begin, int end, const Rows& r, const double* __restrict pos) {
  const __m512d one = _mm512_set1_pd(1.0);
  __m512d table_lo, table_hi, length_lo, length_hi;
  table_registers(r, table_lo, table_hi);
  alignas(64) double lengths[16] = {};
  for (int c = 1; c < std::min(r.classes, 16); ++c) lengths[c] = r.l0[c] > 0.0 ? 1.0 / r.l0[c] : 0.0;
  length_lo = _mm512_load_pd(lengths);
  length_hi = _mm512_load_pd(lengths + 8);
  double sum = 0.0;
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d acc = _mm512_setzero_pd();
    const int64_t last = r.row[i + 1];
    prefetch_rows_ahead<kOffsets>(r, last);
    for (int64_t b = r.row[i]; b < last; b += 8) {
      const Lanes l = load_lanes<true, kOffsets>(r, b, last, i, table_lo, table_hi);
      const __m512d dx = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos, 8), xi);
      const __m512d dy = _mm512_sub_pd(_mm512_i32gather_pd(l.twice_j, pos + 1, 8), yi);
      const __m512d r2 = _mm512_mask_blend_pd(l.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d s = _mm512_fmsub_pd(_mm512_mul_pd(r2, inverse_length(r2)), l.l0, one);
      const __m512i cls = _mm512_cvtepu8_epi64(_mm_maskz_loadu_epi8(__mmask16(l.mask), r.cls + b));
      const __m512d length = _mm512_permutex2var_pd(length_lo, cls, length_hi);
      acc = _mm512_fmadd_pd(_mm512_mul_pd(l.k, length), _mm512_mul_pd(s, s), acc);
    }
    sum += 0.25 * _mm512_reduce_add_pd(acc);
  }
  return sum;
}

// the row maxima when asked for (update_fracture after the step reuses them), else the near test
// of a breaking evaluation
inline Track tracking(const double* most, const RowCut* cut) { return most ? kLargest : cut ? kNear : kNothing; }

// site picks among the twelve compiled variants of an AVX-512 row loop.
template <typename Fn>
void with_avx512_options(const Rows& r, Track track, Fn&& fn) {
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
  if (track == kNear)
    by_table(std::integral_constant<Track, kNear>{});
  else if (track == kLargest)
    by_table(std::integral_constant<Track, kLargest>{});
  else
    by_table(std::integral_constant<Track, kNothing>{});
}

}  // namespace

void elastic_rows_avx512(int begin, int end, const Rows& r, const double* pos, double* force, double* most,
                         const RowCut* cut) {
  with_avx512_options(r, tracking(most, cut), [&](auto track, auto small, auto offsets) {
    elastic_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, force, most, cut);
  });
}

void damped_rows_avx512(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                        double* force, double* most, const RowCut* cut) {
  with_avx512_options(r, tracking(most, cut), [&](auto track, auto small, auto offsets) {
    damped_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, vel, eta_over_e, force, most, cut);
  });
}

bool strain_energy_avx512(int begin, int end, const Rows& r, const double* pos, double& sum) {
  if (r.classes > 16) return false;
  sum = r.off ? energy_avx512<true>(begin, end, r, pos) : energy_avx512<false>(begin, end, r, pos);
  return true;
}

void row_max_stretch_avx512(int begin, int end, const Rows& r, const double* pos, double* out) {
  with_avx512_options(r, kNothing, [&](auto, auto small, auto offsets) {
    row_max_avx512<small.value, offsets.value>(begin, end, r, pos, out);
  });
}

}  // namespace periflex

#endif
