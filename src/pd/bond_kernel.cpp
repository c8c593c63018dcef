#include "pd/bond_kernel.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

// On x86-64 with GCC or Clang the two hottest row loops also exist as AVX2 code (4 doubles a
// vector, hardware gathers, vector square root), chosen at run time when the CPU has AVX2. The
// portable loops stay scalar-ish: std::sqrt may set errno, which keeps GCC from vectorising it
// without -fno-math-errno, a flag the build does not set.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PERIFLEX_HAVE_AVX2_KERNEL 1
#include <immintrin.h>
#endif

namespace periflex {

namespace {

// Below this many particles a loop runs on one thread: fork and join would cost more than the work.
constexpr int kParallelMin = 4096;

// Calls fn(begin, end) over [0, n) split into one contiguous block per thread (the same
// blocks a static schedule would give), or once when n is small.
template <typename Fn>
void for_blocks(int n, Fn&& fn) {
  if (n < kParallelMin) {
    fn(0, n);
    return;
  }
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), id = omp_get_thread_num();
    const int begin = static_cast<int>(static_cast<long>(n) * id / threads);
    const int end = static_cast<int>(static_cast<long>(n) * (id + 1) / threads);
    fn(begin, end);
  }
}

// k (1/|xi| - 1/|y|) y = k s y/|y|: one square root and one division per bond, no branch
// (a broken bond has k = 0). With kTrack the largest stretch over the row's intact bonds
// (at most 0 when none) goes to most[i] as a by-product; the stretch itself is computed exactly
// as break_stretched_bonds computes it.
template <bool kTrack>
void elastic_rows(int begin, int end, const int64_t* __restrict row, const int32_t* __restrict nbr,
                  const double* __restrict inv_len0, const double* __restrict k, const double* __restrict pos,
                  double* __restrict force, double* __restrict most) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double fx = 0.0, fy = 0.0, top = -1.0;
#pragma omp simd reduction(+ : fx, fy) reduction(max : top)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double f = k[b] * (inv_len0[b] - 1.0 / len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k[b] > 0.0 ? len * inv_len0[b] - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// as elastic_rows, plus k eta/E ds/dt with ds/dt = e . (v_j - v_i) / |xi|, along e
template <bool kTrack>
void damped_rows(int begin, int end, const int64_t* __restrict row, const int32_t* __restrict nbr,
                 const double* __restrict inv_len0, const double* __restrict k, const double* __restrict pos,
                 const double* __restrict vel, double eta_over_e, double* __restrict force,
                 double* __restrict most) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const double vxi = vel[2 * i], vyi = vel[2 * i + 1];
    double fx = 0.0, fy = 0.0, top = -1.0;
#pragma omp simd reduction(+ : fx, fy) reduction(max : top)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv_len = 1.0 / len;
      const double rate = (dx * dvx + dy * dvy) * inv_len * inv_len0[b];
      const double f = k[b] * ((inv_len0[b] - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k[b] > 0.0 ? len * inv_len0[b] - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// largest stretch over the intact bonds (k > 0) of each row; -1 for a row without any
void row_max_stretch(int begin, int end, const int64_t* __restrict row, const int32_t* __restrict nbr,
                     const double* __restrict inv_len0, const double* __restrict k, const double* __restrict pos,
                     double* __restrict out) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double most = -1.0;
#pragma omp simd reduction(max : most)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double s = std::sqrt(dx * dx + dy * dy) * inv_len0[b] - 1.0;
      most = std::max(most, k[b] > 0.0 ? s : -1.0);
    }
    out[i] = most;
  }
}

#ifdef PERIFLEX_HAVE_AVX2_KERNEL
// four doubles at base[idx[k]]. The merge source is an explicit zero: with the plain intrinsic
// GCC may pick a register still holding last iteration's result as the (unused) merge source,
// which chains every gather to the previous square root and division and runs 3-4x slower.
__attribute__((target("avx2"))) inline __m256d gather(const double* base, __m128i idx) {
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, idx, all, 8);
}

// sum of the four lanes, in a fixed order
__attribute__((target("avx2"))) inline double lane_sum(__m256d v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
  const __m128d pair = _mm_add_pd(lo, hi);
  return _mm_cvtsd_f64(_mm_add_sd(pair, _mm_unpackhi_pd(pair, pair)));
}

// the stretch lanes of intact bonds (k > 0), 0 for broken ones (a bitwise and with the mask)
__attribute__((target("avx2"))) inline __m256d intact_stretch(__m256d len, __m256d l0, __m256d k) {
  const __m256d s = _mm256_sub_pd(_mm256_mul_pd(len, l0), _mm256_set1_pd(1.0));
  return _mm256_and_pd(s, _mm256_cmp_pd(k, _mm256_setzero_pd(), _CMP_GT_OQ));
}

// the largest of four lanes
__attribute__((target("avx2"))) inline double lane_max(__m256d v) {
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, v);
  return std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
}

// elastic_rows four bonds at a time: gather the neighbours' x and y by index 2j, then the
// same arithmetic lane-wise; the last (row length mod 4) bonds run scalar
template <bool kTrack>
__attribute__((target("avx2"))) void elastic_rows_avx2(int begin, int end, const int64_t* __restrict row,
                                                       const int32_t* __restrict nbr,
                                                       const double* __restrict inv_len0,
                                                       const double* __restrict k, const double* __restrict pos,
                                                       double* __restrict force, double* __restrict most) {
  const __m256d one = _mm256_set1_pd(1.0);
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi);
    __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    int64_t b = row[i];
    const int64_t last = row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather(pos, twice_j), vxi);
      const __m256d dy = _mm256_sub_pd(gather(pos + 1, twice_j), vyi);
      const __m256d r2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      const __m256d len = _mm256_sqrt_pd(r2);
      const __m256d l0 = _mm256_loadu_pd(inv_len0 + b), kb = _mm256_loadu_pd(k + b);
      const __m256d f = _mm256_mul_pd(kb, _mm256_sub_pd(l0, _mm256_div_pd(one, len)));
      ax = _mm256_add_pd(ax, _mm256_mul_pd(f, dx));
      ay = _mm256_add_pd(ay, _mm256_mul_pd(f, dy));
      if constexpr (kTrack) top4 = _mm256_max_pd(top4, intact_stretch(len, l0, kb));
    }
    double fx = lane_sum(ax), fy = lane_sum(ay);
    double top = kTrack ? lane_max(top4) : -1.0;
    for (; b < last; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double f = k[b] * (inv_len0[b] - 1.0 / len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k[b] > 0.0 ? len * inv_len0[b] - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// damped_rows four bonds at a time, like elastic_rows_avx2 with the neighbours' velocities
template <bool kTrack>
__attribute__((target("avx2"))) void damped_rows_avx2(int begin, int end, const int64_t* __restrict row,
                                                      const int32_t* __restrict nbr,
                                                      const double* __restrict inv_len0, const double* __restrict k,
                                                      const double* __restrict pos, const double* __restrict vel,
                                                      double eta_over_e, double* __restrict force,
                                                      double* __restrict most) {
  const __m256d one = _mm256_set1_pd(1.0), eta = _mm256_set1_pd(eta_over_e);
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1], vxi = vel[2 * i], vyi = vel[2 * i + 1];
    const __m256d pxi = _mm256_set1_pd(xi), pyi = _mm256_set1_pd(yi);
    const __m256d qxi = _mm256_set1_pd(vxi), qyi = _mm256_set1_pd(vyi);
    __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), top4 = _mm256_set1_pd(-1.0);
    int64_t b = row[i];
    const int64_t last = row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather(pos, twice_j), pxi);
      const __m256d dy = _mm256_sub_pd(gather(pos + 1, twice_j), pyi);
      const __m256d dvx = _mm256_sub_pd(gather(vel, twice_j), qxi);
      const __m256d dvy = _mm256_sub_pd(gather(vel + 1, twice_j), qyi);
      const __m256d r2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      const __m256d len = _mm256_sqrt_pd(r2);
      const __m256d inv_len = _mm256_div_pd(one, len);
      const __m256d l0 = _mm256_loadu_pd(inv_len0 + b), kb = _mm256_loadu_pd(k + b);
      const __m256d dot = _mm256_add_pd(_mm256_mul_pd(dx, dvx), _mm256_mul_pd(dy, dvy));
      const __m256d rate = _mm256_mul_pd(_mm256_mul_pd(dot, inv_len), l0);
      const __m256d f = _mm256_mul_pd(
          kb, _mm256_add_pd(_mm256_sub_pd(l0, inv_len), _mm256_mul_pd(_mm256_mul_pd(eta, rate), inv_len)));
      ax = _mm256_add_pd(ax, _mm256_mul_pd(f, dx));
      ay = _mm256_add_pd(ay, _mm256_mul_pd(f, dy));
      if constexpr (kTrack) top4 = _mm256_max_pd(top4, intact_stretch(len, l0, kb));
    }
    double fx = lane_sum(ax), fy = lane_sum(ay);
    double top = kTrack ? lane_max(top4) : -1.0;
    for (; b < last; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv_len = 1.0 / len;
      const double rate = (dx * dvx + dy * dvy) * inv_len * inv_len0[b];
      const double f = k[b] * ((inv_len0[b] - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
      if constexpr (kTrack) top = std::max(top, k[b] > 0.0 ? len * inv_len0[b] - 1.0 : -1.0);
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
    if constexpr (kTrack) most[i] = top;
  }
}

// row_max_stretch four bonds at a time; broken bonds (k = 0) count as 0
__attribute__((target("avx2"))) void row_max_stretch_avx2(int begin, int end, const int64_t* __restrict row,
                                                          const int32_t* __restrict nbr,
                                                          const double* __restrict inv_len0,
                                                          const double* __restrict k,
                                                          const double* __restrict pos, double* __restrict out) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi);
    __m256d most4 = _mm256_set1_pd(-1.0);
    int64_t b = row[i];
    const int64_t last = row[i + 1];
    for (; b + 4 <= last; b += 4) {
      const __m128i twice_j = _mm_slli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(nbr + b)), 1);
      const __m256d dx = _mm256_sub_pd(gather(pos, twice_j), vxi);
      const __m256d dy = _mm256_sub_pd(gather(pos + 1, twice_j), vyi);
      const __m256d r2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      most4 = _mm256_max_pd(most4, intact_stretch(_mm256_sqrt_pd(r2), _mm256_loadu_pd(inv_len0 + b),
                                                  _mm256_loadu_pd(k + b)));
    }
    double most = lane_max(most4);
    for (; b < last; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double s = std::sqrt(dx * dx + dy * dy) * inv_len0[b] - 1.0;
      most = std::max(most, k[b] > 0.0 ? s : -1.0);
    }
    out[i] = most;
  }
}

#endif

// set by set_vector_kernels_enabled
std::atomic<bool> vector_kernels_enabled{true};

// true when the AVX2 loops are built, allowed and the CPU runs them (the CPU is asked once)
bool have_avx2() {
#ifdef PERIFLEX_HAVE_AVX2_KERNEL
  static const bool cpu = __builtin_cpu_supports("avx2");
  return cpu && vector_kernels_enabled.load(std::memory_order_relaxed);
#else
  return false;
#endif
}

// the stretch of bond b of particle i, computed the same way for both of its copies
inline double stretch(const BondStore& bonds, const double* pos, int i, int64_t b) {
  const int32_t j = bonds.neighbor[b];
  const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
  return std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b] - 1.0;
}

}  // namespace

void set_vector_kernels_enabled(bool enabled) { vector_kernels_enabled = enabled; }

void add_bond_forces(const BondStore& bonds, const double* pos, double* force, double* row_max) {
  const int64_t* row = bonds.row.data();
  const int32_t* nbr = bonds.neighbor.data();
  const double *l0 = bonds.inv_length.data(), *k = bonds.stiffness.data();
  double* most = row_max;
  for_blocks(bonds.particle_count(), [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_AVX2_KERNEL
    if (have_avx2()) {
      if (most)
        elastic_rows_avx2<true>(begin, end, row, nbr, l0, k, pos, force, most);
      else
        elastic_rows_avx2<false>(begin, end, row, nbr, l0, k, pos, force, most);
      return;
    }
#endif
    if (most)
      elastic_rows<true>(begin, end, row, nbr, l0, k, pos, force, most);
    else
      elastic_rows<false>(begin, end, row, nbr, l0, k, pos, force, most);
  });
}

void add_damped_bond_forces(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e,
                            double* force, double* row_max) {
  const int64_t* row = bonds.row.data();
  const int32_t* nbr = bonds.neighbor.data();
  const double *l0 = bonds.inv_length.data(), *k = bonds.stiffness.data();
  double* most = row_max;
  for_blocks(bonds.particle_count(), [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_AVX2_KERNEL
    if (have_avx2()) {
      if (most)
        damped_rows_avx2<true>(begin, end, row, nbr, l0, k, pos, vel, eta_over_e, force, most);
      else
        damped_rows_avx2<false>(begin, end, row, nbr, l0, k, pos, vel, eta_over_e, force, most);
      return;
    }
#endif
    if (most)
      damped_rows<true>(begin, end, row, nbr, l0, k, pos, vel, eta_over_e, force, most);
    else
      damped_rows<false>(begin, end, row, nbr, l0, k, pos, vel, eta_over_e, force, most);
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
      local += bonds.stiffness[b] * s * s / bonds.inv_length[b];
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
      const double rate = (dx * dvx + dy * dvy) / std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b];
      local += bonds.stiffness[b] * eta_over_e * rate * rate / bonds.inv_length[b];
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
  // a vectorised pass (or the force evaluation at the same positions) finds the rows holding an
  // intact bond beyond s0; only those are walked bond by bond. Both copies of a bond see the same
  // stretch bit for bit, so both rows are walked and both copies break here.
  std::vector<double> computed;
  if (!row_max) computed.resize(n);
  const double* most = row_max ? row_max : computed.data();
  if (!row_max) for_blocks(n, [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_AVX2_KERNEL
    if (have_avx2()) {
      row_max_stretch_avx2(begin, end, bonds.row.data(), bonds.neighbor.data(), bonds.inv_length.data(),
                           bonds.stiffness.data(), pos, computed.data());
      return;
    }
#endif
    row_max_stretch(begin, end, bonds.row.data(), bonds.neighbor.data(), bonds.inv_length.data(),
                    bonds.stiffness.data(), pos, computed.data());
  });
  for (int i = 0; i < n; ++i) {
    if (most[i] <= s0 || (no_fail && no_fail[i])) continue;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (bonds.broken[b] || (no_fail && no_fail[bonds.neighbor[b]])) continue;
      const double s = stretch(bonds, pos, i, b);
      if (s > s0) {
        energy += 0.25 * bonds.stiffness[b] * s * s / bonds.inv_length[b];
        bonds.broken[b] = 1;
        bonds.stiffness[b] = 0.0;
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
  for_blocks(n, [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_AVX2_KERNEL
    if (have_avx2()) {
      row_max_stretch_avx2(begin, end, bonds.row.data(), bonds.neighbor.data(), bonds.inv_length.data(),
                           bonds.stiffness.data(), pos, most.data());
      return;
    }
#endif
    row_max_stretch(begin, end, bonds.row.data(), bonds.neighbor.data(), bonds.inv_length.data(),
                    bonds.stiffness.data(), pos, most.data());
  });
  for (int i = 0; i < n; ++i) out[i] = static_cast<float>(std::max(most[i], 0.0));
}

}  // namespace periflex
