#include "pd/bond_kernel.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

// On x86-64 with GCC or Clang the row loops also exist as AVX-512 code (eight bonds a vector)
// and AVX2 code (four), chosen at run time by what the CPU has. The portable loops stay
// scalar-ish: std::sqrt may set errno, which keeps GCC from vectorising it without
// -fno-math-errno, a flag the build does not set.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PERIFLEX_HAVE_VECTOR_KERNELS 1
#include <immintrin.h>
#endif

namespace periflex {

namespace {

// The row maxima of the vector force loops may differ from the exact stretch by a few units in
// the last place (their 1/|y| is a refined estimate); rows within this much of s0 are walked
// exactly, so both copies of a bond always see the exact stretch when one of them breaks.
constexpr double kRowMaxSlack = 1e-12;

// Below this many particles a loop runs on one thread: fork and join would cost more than the work.
constexpr int kParallelMin = 4096;

// Rows per chunk of a parallel loop: large enough that scheduling costs nothing next to the
// work, small enough (25 chunks at 100k particles) that a thread slowed by another process on
// its core hands its share to the other.
constexpr int kChunkRows = 4096;

// Calls fn(begin, end) over [0, n) in chunks of kChunkRows handed to the threads as they
// become free, or once when n is small. Every row is computed the same way whichever thread
// takes it, so results do not depend on the thread count or the schedule.
template <typename Fn>
void for_blocks(int n, Fn&& fn) {
  if (n < kParallelMin) {
    fn(0, n);
    return;
  }
  const int chunks = (n + kChunkRows - 1) / kChunkRows;
#pragma omp parallel for schedule(dynamic, 1)
  for (int c = 0; c < chunks; ++c) fn(c * kChunkRows, std::min(n, (c + 1) * kChunkRows));
}

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

Rows rows_of(const BondStore& b) {
  return {b.row.data(), b.neighbor.data(), b.neighbor_offset.empty() ? nullptr : b.neighbor_offset.data(),
          b.length_class.data(), b.inv_length_table.data(),
          static_cast<int>(b.inv_length_table.size()), b.stiffness.data()};
}

// k (1/|xi| - 1/|y|) y = k s y/|y|: one square root and one division per bond, no branch
// (a broken bond has k = 0). With kTrack the largest stretch over the row's intact bonds
// (at most 0 when none) goes to most[i] as a by-product.
template <bool kTrack>
void elastic_rows(int begin, int end, const Rows& r, const double* __restrict pos, double* __restrict force,
                  double* __restrict most) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double fx = 0.0, fy = 0.0, top = -1.0;
#pragma omp simd reduction(+ : fx, fy) reduction(max : top)
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double l0 = r.l0[r.cls[b]], k = r.k[b];
      const double f = k * (l0 - 1.0 / len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// as elastic_rows, plus k eta/E ds/dt with ds/dt = e . (v_j - v_i) / |xi|, along e
template <bool kTrack>
void damped_rows(int begin, int end, const Rows& r, const double* __restrict pos, const double* __restrict vel,
                 double eta_over_e, double* __restrict force, double* __restrict most) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const double vxi = vel[2 * i], vyi = vel[2 * i + 1];
    double fx = 0.0, fy = 0.0, top = -1.0;
#pragma omp simd reduction(+ : fx, fy) reduction(max : top)
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv_len = 1.0 / len;
      const double l0 = r.l0[r.cls[b]], k = r.k[b];
      const double rate = (dx * dvx + dy * dvy) * inv_len * l0;
      const double f = k * ((l0 - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// largest stretch over the intact bonds (k > 0) of each row; -1 for a row without any
void row_max_stretch(int begin, int end, const Rows& r, const double* __restrict pos, double* __restrict out) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double most = -1.0;
#pragma omp simd reduction(max : most)
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double s = std::sqrt(dx * dx + dy * dy) * r.l0[r.cls[b]] - 1.0;
      most = std::max(most, r.k[b] > 0.0f ? s : -1.0);
    }
    out[i] = most;
  }
}

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
// ---- AVX2: four bonds a vector, hardware gathers, the scalar loop for the row's remainder ----

// four doubles at base[idx[k]]. The merge source is an explicit zero: with the plain intrinsic
// GCC may pick a register still holding last iteration's result as the (unused) merge source,
// which chains every gather to the previous square root and division and runs 3-4x slower.
__attribute__((target("avx2"))) inline __m256d gather(const double* base, __m128i idx) {
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, idx, all, 8);
}

// 1/|xi| of bonds b .. b+3 from the class table
__attribute__((target("avx2"))) inline __m256d table_lengths(const Rows& r, int64_t b) {
  int32_t four;
  std::memcpy(&four, r.cls + b, sizeof(four));
  return gather(r.l0, _mm_cvtepu8_epi32(_mm_cvtsi32_si128(four)));
}

// sum of the four lanes, in a fixed order
__attribute__((target("avx2"))) inline double lane_sum(__m256d v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
  const __m128d pair = _mm_add_pd(lo, hi);
  return _mm_cvtsd_f64(_mm_add_sd(pair, _mm_unpackhi_pd(pair, pair)));
}

// the stretch lanes of intact bonds (k > 0), -1 for broken ones
__attribute__((target("avx2"))) inline __m256d intact_stretch(__m256d len, __m256d l0, __m256d k) {
  const __m256d s = _mm256_sub_pd(_mm256_mul_pd(len, l0), _mm256_set1_pd(1.0));
  return _mm256_blendv_pd(_mm256_set1_pd(-1.0), s, _mm256_cmp_pd(k, _mm256_setzero_pd(), _CMP_GT_OQ));
}

// the largest of four lanes
__attribute__((target("avx2"))) inline double lane_max(__m256d v) {
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, v);
  return std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
}

template <bool kTrack>
__attribute__((target("avx2"))) void elastic_rows_avx2(int begin, int end, const Rows& r,
                                                       const double* __restrict pos, double* __restrict force,
                                                       double* __restrict most) {
  const __m256d one = _mm256_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const __m256d vxi = _mm256_set1_pd(pos[2 * i]), vyi = _mm256_set1_pd(pos[2 * i + 1]);
    __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    int64_t b = r.row[i];
    const int64_t last = r.row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r.nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather(pos, twice_j), vxi);
      const __m256d dy = _mm256_sub_pd(gather(pos + 1, twice_j), vyi);
      const __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
      const __m256d l0 = table_lengths(r, b), kb = _mm256_cvtps_pd(_mm_loadu_ps(r.k + b));
      const __m256d f = _mm256_mul_pd(kb, _mm256_sub_pd(l0, _mm256_div_pd(one, len)));
      ax = _mm256_add_pd(ax, _mm256_mul_pd(f, dx));
      ay = _mm256_add_pd(ay, _mm256_mul_pd(f, dy));
      if constexpr (kTrack) top4 = _mm256_max_pd(top4, intact_stretch(len, l0, kb));
    }
    double fx = lane_sum(ax), fy = lane_sum(ay), top = kTrack ? lane_max(top4) : -1.0;
    // the remainder, scalar (same formula as elastic_rows)
    for (; b < last; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double len = std::sqrt(dx * dx + dy * dy);
      const double l0 = r.l0[r.cls[b]], k = r.k[b];
      const double f = k * (l0 - 1.0 / len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

template <bool kTrack>
__attribute__((target("avx2"))) void damped_rows_avx2(int begin, int end, const Rows& r,
                                                      const double* __restrict pos, const double* __restrict vel,
                                                      double eta_over_e, double* __restrict force,
                                                      double* __restrict most) {
  const __m256d one = _mm256_set1_pd(1.0), eta = _mm256_set1_pd(eta_over_e);
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1], vxi = vel[2 * i], vyi = vel[2 * i + 1];
    const __m256d pxi = _mm256_set1_pd(xi), pyi = _mm256_set1_pd(yi);
    const __m256d qxi = _mm256_set1_pd(vxi), qyi = _mm256_set1_pd(vyi);
    __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    int64_t b = r.row[i];
    const int64_t last = r.row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r.nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather(pos, twice_j), pxi);
      const __m256d dy = _mm256_sub_pd(gather(pos + 1, twice_j), pyi);
      const __m256d dvx = _mm256_sub_pd(gather(vel, twice_j), qxi);
      const __m256d dvy = _mm256_sub_pd(gather(vel + 1, twice_j), qyi);
      const __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
      const __m256d inv_len = _mm256_div_pd(one, len);
      const __m256d l0 = table_lengths(r, b), kb = _mm256_cvtps_pd(_mm_loadu_ps(r.k + b));
      const __m256d dot = _mm256_add_pd(_mm256_mul_pd(dx, dvx), _mm256_mul_pd(dy, dvy));
      const __m256d rate = _mm256_mul_pd(_mm256_mul_pd(dot, inv_len), l0);
      const __m256d f = _mm256_mul_pd(
          kb, _mm256_add_pd(_mm256_sub_pd(l0, inv_len), _mm256_mul_pd(_mm256_mul_pd(eta, rate), inv_len)));
      ax = _mm256_add_pd(ax, _mm256_mul_pd(f, dx));
      ay = _mm256_add_pd(ay, _mm256_mul_pd(f, dy));
      if constexpr (kTrack) top4 = _mm256_max_pd(top4, intact_stretch(len, l0, kb));
    }
    double fx = lane_sum(ax), fy = lane_sum(ay), top = kTrack ? lane_max(top4) : -1.0;
    for (; b < last; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv_len = 1.0 / len;
      const double l0 = r.l0[r.cls[b]], k = r.k[b];
      const double rate = (dx * dvx + dy * dvy) * inv_len * l0;
      const double f = k * ((l0 - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
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

template <bool kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void elastic_rows_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                         double* __restrict force, double* __restrict most) {
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
    force[2 * i] += _mm512_reduce_add_pd(ax);
    force[2 * i + 1] += _mm512_reduce_add_pd(ay);
    if constexpr (kTrack) most[i] = _mm512_reduce_max_pd(top);
  }
}

template <bool kTrack, bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void damped_rows_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
                                        const double* __restrict vel, double eta_over_e, double* __restrict force,
                                        double* __restrict most) {
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
    force[2 * i] += _mm512_reduce_add_pd(ax);
    force[2 * i + 1] += _mm512_reduce_add_pd(ay);
    if constexpr (kTrack) most[i] = _mm512_reduce_max_pd(top);
  }
}

template <bool kSmallTable, bool kOffsets>
PERIFLEX_AVX512 void row_max_stretch_avx512(int begin, int end, const Rows& r, const double* __restrict pos,
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

#endif

using Isa = VectorKernels;

// set by set_vector_kernels
std::atomic<Isa> widest_allowed{Isa::kAvx512};

// Which row loops run: the widest the build has, the CPU runs and set_vector_kernels allows.
Isa isa() {
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
  static const Isa cpu = (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                          __builtin_cpu_supports("avx512vl"))
                             ? Isa::kAvx512
                         : __builtin_cpu_supports("avx2") ? Isa::kAvx2
                                                          : Isa::kPortable;
  return std::min(cpu, widest_allowed.load(std::memory_order_relaxed));
#else
  return Isa::kPortable;
#endif
}

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
// Calls fn(track, small_table, offsets) with each flag as a std::bool_constant, so one call
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
#endif

// the stretch of bond b of particle i, computed the same way for both of its copies
inline double stretch(const BondStore& bonds, const double* pos, int i, int64_t b) {
  const int32_t j = bonds.neighbor[b];
  const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
  return std::sqrt(dx * dx + dy * dy) * bonds.inv_length(b) - 1.0;
}

// Largest stretch of each row into out.
void row_maxima(const BondStore& bonds, const double* pos, double* out) {
  const Rows r = rows_of(bonds);
  const Isa which = isa();
  for_blocks(bonds.particle_count(), [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
    if (which == Isa::kAvx512) {
      return with_avx512_options(r, false, [&](auto, auto small, auto offsets) {
        row_max_stretch_avx512<small.value, offsets.value>(begin, end, r, pos, out);
      });
    }
#endif
    row_max_stretch(begin, end, r, pos, out);
  });
}

}  // namespace

void set_vector_kernels(VectorKernels widest) { widest_allowed = widest; }
void set_vector_kernels_enabled(bool enabled) { set_vector_kernels(enabled ? Isa::kAvx512 : Isa::kPortable); }

void add_bond_forces(const BondStore& bonds, const double* pos, double* force, double* row_max, double* pos_copy) {
  const Rows r = rows_of(bonds);
  const Isa which = isa();
  for_blocks(bonds.particle_count(), [&](int begin, int end) {
    if (pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, pos_copy + 2 * begin);
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
    if (which == Isa::kAvx512) {
      return with_avx512_options(r, row_max != nullptr, [&](auto track, auto small, auto offsets) {
        elastic_rows_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, force, row_max);
      });
    }
    if (which == Isa::kAvx2) {
      if (row_max) return elastic_rows_avx2<true>(begin, end, r, pos, force, row_max);
      return elastic_rows_avx2<false>(begin, end, r, pos, force, row_max);
    }
#endif
    if (row_max) return elastic_rows<true>(begin, end, r, pos, force, row_max);
    elastic_rows<false>(begin, end, r, pos, force, row_max);
  });
}

void add_damped_bond_forces(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e,
                            double* force, double* row_max, double* pos_copy) {
  const Rows r = rows_of(bonds);
  const Isa which = isa();
  for_blocks(bonds.particle_count(), [&](int begin, int end) {
    if (pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, pos_copy + 2 * begin);
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
    if (which == Isa::kAvx512) {
      return with_avx512_options(r, row_max != nullptr, [&](auto track, auto small, auto offsets) {
        damped_rows_avx512<track.value, small.value, offsets.value>(begin, end, r, pos, vel, eta_over_e, force,
                                                                       row_max);
      });
    }
    if (which == Isa::kAvx2) {
      if (row_max) return damped_rows_avx2<true>(begin, end, r, pos, vel, eta_over_e, force, row_max);
      return damped_rows_avx2<false>(begin, end, r, pos, vel, eta_over_e, force, row_max);
    }
#endif
    if (row_max) return damped_rows<true>(begin, end, r, pos, vel, eta_over_e, force, row_max);
    damped_rows<false>(begin, end, r, pos, vel, eta_over_e, force, row_max);
  });
}

double bond_strain_energy(const BondStore& bonds, const double* pos) {
  const int n = bonds.particle_count();
  double sum = 0.0;
  // each pair is visited twice: a quarter of k |xi| s^2 per visit
#pragma omp parallel for schedule(static) reduction(+ : sum) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    double local = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const double s = stretch(bonds, pos, i, b);
      local += double(bonds.stiffness[b]) * s * s / bonds.inv_length(b);
    }
    sum += 0.25 * local;
  }
  return sum;
}

double bond_damping_power(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e) {
  const int n = bonds.particle_count();
  double sum = 0.0;
  // k eta/E |xi| (ds/dt)^2 per pair, half per visit
#pragma omp parallel for schedule(static) reduction(+ : sum) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    double local = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
      const double l0 = bonds.inv_length(b);
      const double rate = (dx * dvx + dy * dvy) / std::sqrt(dx * dx + dy * dy) * l0;
      local += double(bonds.stiffness[b]) * eta_over_e * rate * rate / l0;
    }
    sum += 0.5 * local;
  }
  return sum;
}

long break_stretched_bonds(BondStore& bonds, const double* pos, double s0, const uint8_t* no_fail,
                           double& energy_released, const double* row_max) {
  const int n = bonds.particle_count();
  long directed = 0;
  double energy = 0.0;
  // a pass over the rows (or the force evaluation at the same positions) finds the rows holding
  // an intact bond near or beyond s0; only those are walked bond by bond, with the exact
  // stretch. Both copies of a bond see the same stretch bit for bit, so both rows are walked and
  // both copies break here.
  std::vector<double> computed;
  if (!row_max) {
    computed.resize(n);
    row_maxima(bonds, pos, computed.data());
  }
  const double* most = row_max ? row_max : computed.data();
  for (int i = 0; i < n; ++i) {
    if (most[i] <= s0 - kRowMaxSlack || (no_fail && no_fail[i])) continue;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (bonds.broken[b] || (no_fail && no_fail[bonds.neighbor[b]])) continue;
      const double s = stretch(bonds, pos, i, b);
      if (s > s0) {
        energy += 0.25 * double(bonds.stiffness[b]) * s * s / bonds.inv_length(b);
        bonds.broken[b] = 1;
        bonds.stiffness[b] = 0.0f;
        ++directed;
      }
    }
  }
  energy_released = energy;
  return directed / 2;
}

void max_bond_stretch(const BondStore& bonds, const double* pos, float* out) {
  const int n = bonds.particle_count();
  std::vector<double> most(n);
  row_maxima(bonds, pos, most.data());
  for (int i = 0; i < n; ++i) out[i] = static_cast<float>(std::max(most[i], 0.0));
}

}  // namespace periflex
