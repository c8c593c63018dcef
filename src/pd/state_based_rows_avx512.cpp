// The state-based row loops eight bonds at a time with AVX-512 (see state_based_rows.h).
#include <immintrin.h>

#include <algorithm>

#include "pd/bond_prefetch.h"
#include "pd/state_based_rows.h"

#ifdef PERIFLEX_HAVE_LPS_AVX512

namespace periflex {

namespace {

#define PERIFLEX_LPS_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,fma")))

// |y| comes from the square root and 1/|y| from the division, which run on a unit of their own beside
// the multiply-add units the rest of a block keeps busy, instead of the hardware estimate of 1/|y|
// refined by two Newton steps (eight multiply-adds a vector). With the 256-bit row tails below, the
// loops ran 1.11-1.15x faster per bond (docs/peridynamics.md, state-based speed).

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

// One block of up to eight bonds [b, min(b + 8, last)): masked-off lanes take the particle itself
// (load_points), w = 0 and class 0, so they add nothing.
struct Block {
  __mmask8 mask;
  __m512i cls;  // length class
  __m512d w;    // bond weight, 0 once broken or masked
};

PERIFLEX_LPS_AVX512 inline Block load_block(const BondStore& bonds, const BondState& live, int64_t b, int64_t last) {
  Block k;
  const int64_t left = last - b;
  k.mask = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
  k.cls = _mm512_cvtepu8_epi64(_mm_maskz_loadu_epi8(__mmask16(k.mask), bonds.length_class.data() + b));
  k.w = _mm512_cvtps_pd(_mm256_maskz_loadu_ps(k.mask, live.stiffness.data() + b));
  return k;
}

// the bond arrays some rows past bond b, fetched ahead of the loop (bond_prefetch.h)
template <bool kOffsets>
inline void prefetch_bonds(const BondStore& bonds, const BondState& live, int64_t b) {
  if constexpr (kOffsets)
    prefetch_bonds_ahead(live.stiffness.data(), bonds.length_class.data(), bonds.neighbor_offset.data(), b);
  else
    prefetch_bonds_ahead(live.stiffness.data(), bonds.length_class.data(), bonds.neighbor.data(), b);
}

// Neighbour j of lane k of the block starting at bond b (the particle itself past the row's end).
template <bool kOffsets>
inline int lane_neighbor(const BondStore& bonds, int64_t b, int64_t left, int k, int i) {
  if (k >= left) return i;
  return kOffsets ? i + bonds.neighbor_offset[b + k] : bonds.neighbor[b + k];
}

// x and y of eight neighbours (lane k: neighbour k) from one 16-byte load each and a deinterleave
// in registers, instead of two gathers of eight.
PERIFLEX_LPS_AVX512 inline __m512d four_points(const double* pos, const int* j) {
  const __m512d z = _mm512_castpd128_pd512(_mm_loadu_pd(pos + 2 * static_cast<int64_t>(j[0])));
  const __m512d z1 = _mm512_insertf64x2(z, _mm_loadu_pd(pos + 2 * static_cast<int64_t>(j[1])), 1);
  const __m512d z2 = _mm512_insertf64x2(z1, _mm_loadu_pd(pos + 2 * static_cast<int64_t>(j[2])), 2);
  return _mm512_insertf64x2(z2, _mm_loadu_pd(pos + 2 * static_cast<int64_t>(j[3])), 3);
}

template <bool kOffsets>
PERIFLEX_LPS_AVX512 inline void load_points(const BondStore& bonds, const double* pos, int64_t b, int64_t left, int i,
                                            __m512d& x, __m512d& y) {
  int j[8];
  for (int k = 0; k < 8; ++k) j[k] = lane_neighbor<kOffsets>(bonds, b, left, k, i);
  // [x0 y0 x1 y1 x2 y2 x3 y3] and [x4 y4 ... y7] -> [x0 ... x7], [y0 ... y7]
  const __m512d lo = four_points(pos, j), hi = four_points(pos, j + 4);
  x = _mm512_permutex2var_pd(lo, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), hi);
  y = _mm512_permutex2var_pd(lo, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), hi);
}

// A row's last block of at most four bonds [b, b + left), left in 1..4: as Block, the weights in 256
// bits; the classes stay in a 512-bit register for the class-table permute (upper lanes unused).
struct TailBlock {
  __mmask8 mask;
  __m512i cls;
  __m256d w;
};

PERIFLEX_LPS_AVX512 inline TailBlock load_tail(const BondStore& bonds, const BondState& live, int64_t b, int64_t left) {
  TailBlock k;
  k.mask = __mmask8((1u << left) - 1u);
  const __m128i bytes = _mm_maskz_loadu_epi8(__mmask16(k.mask), bonds.length_class.data() + b);
  k.cls = _mm512_castsi256_si512(_mm256_cvtepu8_epi64(bytes));
  k.w = _mm256_cvtps_pd(_mm_maskz_loadu_ps(k.mask, live.stiffness.data() + b));
  return k;
}

// sum of the four lanes
PERIFLEX_LPS_AVX512 inline double lane_sum(__m256d v) {
  const __m128d h = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_add_sd(h, _mm_unpackhi_pd(h, h)));
}

// largest of the four lanes
PERIFLEX_LPS_AVX512 inline double lane_max(__m256d v) {
  const __m128d h = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_max_sd(h, _mm_unpackhi_pd(h, h)));
}

// The last (at most four) bonds of a row in 256-bit vectors (see force_tail below): adds
// w |xi| (|y| - |xi|) to acc and, with kTrack, folds the intact bonds' stretch into top.
template <bool kTrack, bool kOffsets>
PERIFLEX_LPS_AVX512 inline void extension_tail(const BondStore& bonds, const BondState& live, const double* pos,
                                               const ClassTables& t,
                                               int64_t b, int64_t last, int i, __m256d& acc, __m256d& top) {
  const int64_t left = last - b;
  const TailBlock tail = load_tail(bonds, live, b, left);
  const __m512i cls = tail.cls;
  const __m256d w = tail.w;
  const __m256d x0 = _mm512_castpd512_pd256(_mm512_permutex2var_pd(t.length_lo, cls, t.length_hi));
  int j[4];
  for (int k = 0; k < 4; ++k) j[k] = lane_neighbor<kOffsets>(bonds, b, left, k, i);
  // [x0 y0 x2 y2] and [x1 y1 x3 y3] -> [x0 x1 x2 x3], [y0 y1 y2 y3]
  auto point = [pos](int k) { return _mm_loadu_pd(pos + 2 * static_cast<int64_t>(k)); };
  const __m256d lo = _mm256_insertf128_pd(_mm256_castpd128_pd256(point(j[0])), point(j[2]), 1);
  const __m256d hi = _mm256_insertf128_pd(_mm256_castpd128_pd256(point(j[1])), point(j[3]), 1);
  const __m256d dx = _mm256_sub_pd(_mm256_unpacklo_pd(lo, hi), _mm256_set1_pd(pos[2 * i]));
  const __m256d dy = _mm256_sub_pd(_mm256_unpackhi_pd(lo, hi), _mm256_set1_pd(pos[2 * i + 1]));
  const __m256d len = _mm256_sqrt_pd(_mm256_fmadd_pd(dx, dx, _mm256_mul_pd(dy, dy)));
  acc = _mm256_fmadd_pd(_mm256_mul_pd(w, x0), _mm256_sub_pd(len, x0), acc);
  if constexpr (kTrack) {
    const __m256d inv0 = _mm512_castpd512_pd256(_mm512_permutex2var_pd(t.inv_lo, cls, t.inv_hi));
    const __m256d s = _mm256_fmsub_pd(len, inv0, _mm256_set1_pd(1.0));
    top = _mm256_mask_max_pd(top, _mm256_cmp_pd_mask(w, _mm256_setzero_pd(), _CMP_GT_OQ), top, s);
  }
}

template <bool kTrack, bool kOffsets>
PERIFLEX_LPS_AVX512 void extension_sums(int begin, int end, const BondStore& bonds, const BondState& live,
                                        const double* __restrict pos, double* __restrict sum, double* __restrict most) {
  const ClassTables t = class_tables(bonds);
  const __m512d one = _mm512_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const __m512d xi = _mm512_set1_pd(pos[2 * i]), yi = _mm512_set1_pd(pos[2 * i + 1]);
    __m512d acc = _mm512_setzero_pd(), top = _mm512_set1_pd(-1.0);
    __m256d acc4 = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    const int64_t last = bonds.row[i + 1];
    prefetch_bonds<kOffsets>(bonds, live, last);
    for (int64_t b = bonds.row[i]; b < last; b += 8) {
      if (last - b <= 4) {
        extension_tail<kTrack, kOffsets>(bonds, live, pos, t, b, last, i, acc4, top4);
        break;
      }
      const Block k = load_block(bonds, live, b, last);
      __m512d xj, yj;
      load_points<kOffsets>(bonds, pos, b, last - b, i, xj, yj);
      const __m512d dx = _mm512_sub_pd(xj, xi), dy = _mm512_sub_pd(yj, yi);
      // |y| by the square root unit, which runs beside the multiply-add units (masked lanes: 0)
      const __m512d len = _mm512_sqrt_pd(_mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d x0 = _mm512_permutex2var_pd(t.length_lo, k.cls, t.length_hi);
      // w |xi| (|y| - |xi|)
      acc = _mm512_fmadd_pd(_mm512_mul_pd(k.w, x0), _mm512_sub_pd(len, x0), acc);
      if constexpr (kTrack) {
        const __m512d inv0 = _mm512_permutex2var_pd(t.inv_lo, k.cls, t.inv_hi);
        const __m512d s = _mm512_fmsub_pd(len, inv0, one);
        top = _mm512_mask_max_pd(top, _mm512_cmp_pd_mask(k.w, _mm512_setzero_pd(), _CMP_GT_OQ), top, s);
      }
    }
    sum[i] = _mm512_reduce_add_pd(acc) + lane_sum(acc4);
    if constexpr (kTrack) most[i] = std::max(_mm512_reduce_max_pd(top), lane_max(top4));
  }
}

}  // namespace

PERIFLEX_LPS_AVX512 void lps_extension_sums_avx512(int begin, int end, const BondStore& bonds, const BondState& live,
                                                   const double* pos, double* sum, double* most) {
  const bool offsets = !bonds.neighbor_offset.empty();
  if (most && offsets)
    extension_sums<true, true>(begin, end, bonds, live, pos, sum, most);
  else if (most)
    extension_sums<true, false>(begin, end, bonds, live, pos, sum, most);
  else if (offsets)
    extension_sums<false, true>(begin, end, bonds, live, pos, sum, most);
  else
    extension_sums<false, false>(begin, end, bonds, live, pos, sum, most);
}

namespace {

// The records [x y a b] of eight neighbours as four vectors X, Y, A, B (lane k: neighbour k): one
// 32-byte load per neighbour, then a transpose in registers, instead of four gathers of eight.
struct Neighbors {
  __m512d x, y, a, b;
};

PERIFLEX_LPS_AVX512 inline __m512d two_records(const double* rec, int j0, int j1) {
  return _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j0))),
                            _mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j1)), 1);
}

template <bool kOffsets>
PERIFLEX_LPS_AVX512 inline Neighbors load_neighbors(const BondStore& bonds, const double* rec, int64_t b,
                                                    int64_t left, int i) {
  int j[8];
  for (int k = 0; k < 8; ++k) j[k] = lane_neighbor<kOffsets>(bonds, b, left, k, i);
  // z01 = [x0 y0 a0 b0 x1 y1 a1 b1], z23, z45, z67 likewise
  const __m512d z01 = two_records(rec, j[0], j[1]), z23 = two_records(rec, j[2], j[3]);
  const __m512d z45 = two_records(rec, j[4], j[5]), z67 = two_records(rec, j[6], j[7]);
  // even and odd entries of each 128-bit lane: [x0 x2 a0 a2 x1 x3 a1 a3], [y0 y2 b0 b2 y1 y3 b1 b3]
  const __m512d lo0 = _mm512_unpacklo_pd(z01, z23), hi0 = _mm512_unpackhi_pd(z01, z23);
  const __m512d lo1 = _mm512_unpacklo_pd(z45, z67), hi1 = _mm512_unpackhi_pd(z45, z67);
  const __m512i first = _mm512_setr_epi64(0, 4, 1, 5, 8, 12, 9, 13), second = _mm512_setr_epi64(2, 6, 3, 7, 10, 14, 11, 15);
  return {_mm512_permutex2var_pd(lo0, first, lo1), _mm512_permutex2var_pd(hi0, first, hi1),
          _mm512_permutex2var_pd(lo0, second, lo1), _mm512_permutex2var_pd(hi0, second, hi1)};
}

// The last (at most four) bonds of a row in 256-bit vectors: an interior row has 28 bonds, three
// blocks of eight and four over, and a 512-bit operation costs two 256-bit ones whatever its mask,
// so the half-empty block would cost as much as a full one. Adds the pair forces of bonds
// [b, last) (before the factor V^2) to fx, fy.
template <bool kOffsets>
PERIFLEX_LPS_AVX512 inline void force_tail(const BondStore& bonds, const BondState& live, const double* rec,
                                           const ClassTables& t, int64_t b,
                                           int64_t last, int i, __m256d& fx, __m256d& fy) {
  const int64_t left = last - b;
  const TailBlock tail = load_tail(bonds, live, b, left);
  const __mmask8 mask = tail.mask;
  const __m512i cls = tail.cls;
  const __m256d w = tail.w;
  const __m256d x0 = _mm512_castpd512_pd256(_mm512_permutex2var_pd(t.length_lo, cls, t.length_hi));
  int j[4];
  for (int k = 0; k < 4; ++k) j[k] = lane_neighbor<kOffsets>(bonds, b, left, k, i);
  // four records [x y a b] transposed to X, Y, A, B
  const __m256d q0 = _mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j[0]));
  const __m256d q1 = _mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j[1]));
  const __m256d q2 = _mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j[2]));
  const __m256d q3 = _mm256_loadu_pd(rec + 4 * static_cast<int64_t>(j[3]));
  const __m256d t0 = _mm256_unpacklo_pd(q0, q1), t1 = _mm256_unpackhi_pd(q0, q1);  // [x0 x1 a0 a1], [y0 y1 b0 b1]
  const __m256d t2 = _mm256_unpacklo_pd(q2, q3), t3 = _mm256_unpackhi_pd(q2, q3);  // [x2 x3 a2 a3], [y2 y3 b2 b3]
  const double* o = rec + 4 * static_cast<int64_t>(i);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d dx = _mm256_sub_pd(_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_set1_pd(o[0]));
  const __m256d dy = _mm256_sub_pd(_mm256_permute2f128_pd(t1, t3, 0x20), _mm256_set1_pd(o[1]));
  const __m256d aj = _mm256_add_pd(_mm256_set1_pd(o[2]), _mm256_permute2f128_pd(t0, t2, 0x31));
  const __m256d bj = _mm256_add_pd(_mm256_set1_pd(o[3]), _mm256_permute2f128_pd(t1, t3, 0x31));
  const __m256d r2 = _mm256_mask_blend_pd(mask, one, _mm256_fmadd_pd(dx, dx, _mm256_mul_pd(dy, dy)));
  const __m256d len = _mm256_sqrt_pd(r2);
  const __m256d inv_len = _mm256_div_pd(one, len);
  const __m256d pair = _mm256_fmadd_pd(aj, x0, _mm256_mul_pd(bj, _mm256_sub_pd(len, x0)));
  const __m256d f = _mm256_mul_pd(_mm256_mul_pd(w, pair), inv_len);
  fx = _mm256_fmadd_pd(f, dx, fx);
  fy = _mm256_fmadd_pd(f, dy, fy);
}

template <bool kOffsets>
PERIFLEX_LPS_AVX512 void forces(int begin, int end, const BondStore& bonds, const BondState& live,
                                const double* __restrict rec, double v2, double* __restrict force) {
  const ClassTables t = class_tables(bonds);
  const __m512d one = _mm512_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const double* own = rec + 4 * static_cast<int64_t>(i);
    const __m512d xi = _mm512_set1_pd(own[0]), yi = _mm512_set1_pd(own[1]);
    const __m512d ai = _mm512_set1_pd(own[2]), bi = _mm512_set1_pd(own[3]);
    __m512d fx = _mm512_setzero_pd(), fy = _mm512_setzero_pd();
    __m256d tx = _mm256_setzero_pd(), ty = _mm256_setzero_pd();
    const int64_t last = bonds.row[i + 1];
    prefetch_bonds<kOffsets>(bonds, live, last);
    for (int64_t b = bonds.row[i]; b < last; b += 8) {
      if (last - b <= 4) {
        force_tail<kOffsets>(bonds, live, rec, t, b, last, i, tx, ty);
        break;
      }
      const Block k = load_block(bonds, live, b, last);
      const Neighbors nb = load_neighbors<kOffsets>(bonds, rec, b, last - b, i);
      const __m512d dx = _mm512_sub_pd(nb.x, xi), dy = _mm512_sub_pd(nb.y, yi);
      const __m512d r2 = _mm512_mask_blend_pd(k.mask, one, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      const __m512d len = _mm512_sqrt_pd(r2);
      const __m512d inv_len = _mm512_div_pd(one, len);
      const __m512d x0 = _mm512_permutex2var_pd(t.length_lo, k.cls, t.length_hi);
      const __m512d aj = _mm512_add_pd(ai, nb.a), bj = _mm512_add_pd(bi, nb.b);
      // w ((a_i + a_j) |xi| + (b_i + b_j) (|y| - |xi|)) / |y|
      const __m512d pair = _mm512_fmadd_pd(aj, x0, _mm512_mul_pd(bj, _mm512_sub_pd(len, x0)));
      const __m512d f = _mm512_mul_pd(_mm512_mul_pd(k.w, pair), inv_len);
      fx = _mm512_fmadd_pd(f, dx, fx);
      fy = _mm512_fmadd_pd(f, dy, fy);
    }
    force[2 * i] += v2 * (_mm512_reduce_add_pd(fx) + lane_sum(tx));
    force[2 * i + 1] += v2 * (_mm512_reduce_add_pd(fy) + lane_sum(ty));
  }
}

}  // namespace

PERIFLEX_LPS_AVX512 void lps_forces_avx512(int begin, int end, const BondStore& bonds, const BondState& live,
                                           const double* records, double v2, double* force) {
  if (!bonds.neighbor_offset.empty())
    forces<true>(begin, end, bonds, live, records, v2, force);
  else
    forces<false>(begin, end, bonds, live, records, v2, force);
}

}  // namespace periflex

#endif
