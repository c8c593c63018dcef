// The bond row loops four bonds at a time with AVX2 (see bond_rows.h).
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pd/bond_rows.h"

#ifdef PERIFLEX_HAVE_VECTOR_KERNELS

namespace periflex {

namespace {

// ---- AVX2: four bonds a vector, hardware gathers, the scalar loop for the row's remainder ----

// four doubles at base[idx[k]]. A gather's destination is also the merge source of its masked
// lanes, so a register still holding the previous vector's force chains every gather to the
// previous square root and division (3-4x slower). The zero given as merge source is kept only
// while the compiler cannot see that the mask is all ones: with kFresh the mask is hidden from it,
// and it writes a fresh zero into the destination before each gather. The loops of a body off the
// grid and the damped loops need it (without it the jittered elastic loop took 1.4x as long and
// the damped one 1.2x); the elastic loop on the grid did not chain and keeps the plain form.
template <bool kFresh>
__attribute__((target("avx2"))) inline __m256d gather(const double* base, __m128i idx) {
  __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  if constexpr (kFresh) asm volatile("" : "+x"(all));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, idx, all, 8);
}

// 1/|xi| of bonds b .. b+3 from the class table, or with kOwn (a body off the grid) their own.
// The choice is a template argument, not a test in the loop: a branch there let GCC chain the
// gathers as above and halved the speed of the elastic loop.
template <bool kOwn>
__attribute__((target("avx2"))) inline __m256d table_lengths(const Rows& r, int64_t b) {
  if constexpr (kOwn) return _mm256_loadu_pd(r.own + b);
  int32_t four;
  std::memcpy(&four, r.cls + b, sizeof(four));
  return gather<false>(r.l0, _mm_cvtepu8_epi32(_mm_cvtsi32_si128(four)));
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

template <bool kTrack, bool kOwn>
__attribute__((target("avx2"))) void elastic_avx2(int begin, int end, const Rows& r,
                                                       const double* __restrict pos, double* __restrict force,
                                                       double* __restrict most, const RowCut* cut) {
  const __m256d one = _mm256_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const __m256d vxi = _mm256_set1_pd(pos[2 * i]), vyi = _mm256_set1_pd(pos[2 * i + 1]);
    __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    int64_t b = r.row[i];
    const int64_t last = r.row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r.nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather<kOwn>(pos, twice_j), vxi);
      const __m256d dy = _mm256_sub_pd(gather<kOwn>(pos + 1, twice_j), vyi);
      const __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
      const __m256d l0 = table_lengths<kOwn>(r, b), kb = _mm256_cvtps_pd(_mm_loadu_ps(r.k + b));
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
      const double l0 = kOwn ? r.own[b] : r.l0[r.cls[b]], k = r.k[b];
      const double f = k * (l0 - 1.0 / len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    if constexpr (kTrack) {
      if (most) most[i] = top;
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (cut && top > row_threshold(r, *cut, i) - kCutSlack) {
        fx = fy = 0.0;
        cut_row_forces(i, r, *cut, pos, nullptr, 0.0, fx, fy);
      }
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
  }
}

template <bool kTrack, bool kOwn>
__attribute__((target("avx2"))) void damped_avx2(int begin, int end, const Rows& r,
                                                      const double* __restrict pos, const double* __restrict vel,
                                                      double eta_over_e, double* __restrict force,
                                                      double* __restrict most, const RowCut* cut) {
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
      const __m256d dx = _mm256_sub_pd(gather<true>(pos, twice_j), pxi);
      const __m256d dy = _mm256_sub_pd(gather<true>(pos + 1, twice_j), pyi);
      const __m256d dvx = _mm256_sub_pd(gather<true>(vel, twice_j), qxi);
      const __m256d dvy = _mm256_sub_pd(gather<true>(vel + 1, twice_j), qyi);
      const __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
      const __m256d inv_len = _mm256_div_pd(one, len);
      const __m256d l0 = table_lengths<kOwn>(r, b), kb = _mm256_cvtps_pd(_mm_loadu_ps(r.k + b));
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
      const double l0 = kOwn ? r.own[b] : r.l0[r.cls[b]], k = r.k[b];
      const double rate = (dx * dvx + dy * dvy) * inv_len * l0;
      const double f = k * ((l0 - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k > 0.0 ? len * l0 - 1.0 : -1.0);
    }
    if constexpr (kTrack) {
      if (most) most[i] = top;
      // a row near or past s0 (rare: at a crack tip) is summed again without the bonds that break
      if (cut && top > row_threshold(r, *cut, i) - kCutSlack) {
        fx = fy = 0.0;
        cut_row_forces(i, r, *cut, pos, vel, eta_over_e, fx, fy);
      }
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
  }
}

}  // namespace

void elastic_rows_avx2(int begin, int end, const Rows& r, const double* pos, double* force, double* most,
                       const RowCut* cut) {
  const bool track = most || cut;
  if (r.own)
    track ? elastic_avx2<true, true>(begin, end, r, pos, force, most, cut)
          : elastic_avx2<false, true>(begin, end, r, pos, force, most, cut);
  else
    track ? elastic_avx2<true, false>(begin, end, r, pos, force, most, cut)
          : elastic_avx2<false, false>(begin, end, r, pos, force, most, cut);
}

void damped_rows_avx2(int begin, int end, const Rows& r, const double* pos, const double* vel, double eta_over_e,
                      double* force, double* most, const RowCut* cut) {
  const bool track = most || cut;
  if (r.own)
    track ? damped_avx2<true, true>(begin, end, r, pos, vel, eta_over_e, force, most, cut)
          : damped_avx2<false, true>(begin, end, r, pos, vel, eta_over_e, force, most, cut);
  else
    track ? damped_avx2<true, false>(begin, end, r, pos, vel, eta_over_e, force, most, cut)
          : damped_avx2<false, false>(begin, end, r, pos, vel, eta_over_e, force, most, cut);
}

}  // namespace periflex

#endif
