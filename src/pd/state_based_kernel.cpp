#include "pd/state_based_kernel.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/parallel_chunks.h"
#include "pd/row_blocks.h"
#include "pd/state_based_rows.h"

// This file is built with -fno-math-errno (src/CMakeLists.txt) so that the square roots of the
// row loops vectorise; the loops have no other use for errno.

namespace periflex {

namespace {

// what the row loops read for 1/|xi|: the class of each bond and the class table, or (a body off
// the grid) no classes and each bond's own
inline const uint8_t* cls_of(const BondStore& bonds) {
  return bonds.own_lengths() ? nullptr : bonds.length_class.data();
}
inline const double* l0_of(const BondStore& bonds) {
  return bonds.own_lengths() ? bonds.bond_inv_length.data() : bonds.inv_length_table.data();
}

// |xi| of bond b
inline double ref_length(const BondStore& bonds, int64_t b) { return 1.0 / bonds.inv_length(b); }

// Dilatation rows: theta_i = (2 V / m_i) sum w |xi| (|y| - |xi|), and with kTrack the largest
// stretch over the intact bonds (-1 without any) into most[i]. 1/|xi| of bond b is l0[cls[b]],
// or with kOwn (a body off the grid, cls null) l0[b].
template <bool kTrack, bool kOwn>
inline __attribute__((always_inline)) void dilatation_rows(int begin, int end, const int64_t* __restrict row, const int32_t* __restrict nbr,
                     const uint8_t* __restrict cls, const double* __restrict l0, const float* __restrict w,
                     const double* __restrict m, double volume, const double* __restrict pos,
                     double* __restrict theta, double* __restrict most) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double sum = 0.0, top = -1.0;
#pragma omp simd reduction(+ : sum) reduction(max : top)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv0 = kOwn ? l0[b] : l0[cls[b]], wb = w[b];
      // w |xi| e = w (|y| - |xi|) |xi| = w |xi|^2 (|y| / |xi| - 1)
      const double s = len * inv0 - 1.0;
      sum += wb * s / (inv0 * inv0);
      if constexpr (kTrack) top = std::max(top, wb > 0.0f ? s : -1.0);
    }
    theta[i] = m[i] > 0.0 ? 2.0 * volume * sum / m[i] : 0.0;
    if constexpr (kTrack) most[i] = top;
  }
}

// Force rows: force_i += V^2 sum w ((a_i + a_j) |xi| + (b_i + b_j) (e + eta/E de/dt)) y / |y|;
// 1/|xi| as in dilatation_rows.
template <bool kDamped, bool kOwn>
inline __attribute__((always_inline)) void force_rows(int begin, int end, const int64_t* __restrict row, const int32_t* __restrict nbr,
                const uint8_t* __restrict cls, const double* __restrict l0, const float* __restrict w,
                const double* __restrict a, const double* __restrict bcoef, double v2, const double* __restrict pos,
                const double* __restrict vel, double eta_over_e, double* __restrict force) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const double ai = a[i], bi = bcoef[i];
    double vxi = 0.0, vyi = 0.0;
    if constexpr (kDamped) {
      vxi = vel[2 * i];
      vyi = vel[2 * i + 1];
    }
    double fx = 0.0, fy = 0.0;
#pragma omp simd reduction(+ : fx, fy)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double len = std::sqrt(dx * dx + dy * dy);
      const double inv_len = 1.0 / len;
      const double x0 = 1.0 / (kOwn ? l0[b] : l0[cls[b]]);
      double ext = len - x0;
      if constexpr (kDamped) ext += eta_over_e * (dx * (vel[2 * j] - vxi) + dy * (vel[2 * j + 1] - vyi)) * inv_len;
      const double f = double(w[b]) * ((ai + a[j]) * x0 + (bi + bcoef[j]) * ext) * inv_len;
      fx += f * dx;
      fy += f * dy;
    }
    force[2 * i] += v2 * fx;
    force[2 * i + 1] += v2 * fy;
  }
}

// The two row loops compiled three times: for AVX-512, for AVX2 with FMA, and for the baseline
// ISA, one chosen at run time by what the CPU has. The bodies above are the same for all; the
// compiler vectorises each for its ISA.
struct RowLoops {
  void (*dilatation)(int, int, const int64_t*, const int32_t*, const uint8_t*, const double*, const float*,
                     const double*, double, const double*, double*, double*);
  void (*force)(int, int, const int64_t*, const int32_t*, const uint8_t*, const double*, const float*, const double*,
                const double*, double, const double*, const double*, double, double*);
};

#define PERIFLEX_LPS_ROW_LOOPS(name, target)                                                                       \
  target void name##_dilatation(int begin, int end, const int64_t* row, const int32_t* nbr, const uint8_t* cls,     \
                                const double* l0, const float* w, const double* m, double volume, const double* pos, \
                                double* theta, double* most) {                                                      \
    if (most && cls)                                                                                                \
      dilatation_rows<true, false>(begin, end, row, nbr, cls, l0, w, m, volume, pos, theta, most);                   \
    else if (cls)                                                                                                   \
      dilatation_rows<false, false>(begin, end, row, nbr, cls, l0, w, m, volume, pos, theta, most);                  \
    else if (most)                                                                                                  \
      dilatation_rows<true, true>(begin, end, row, nbr, cls, l0, w, m, volume, pos, theta, most);                    \
    else                                                                                                            \
      dilatation_rows<false, true>(begin, end, row, nbr, cls, l0, w, m, volume, pos, theta, most);                   \
  }                                                                                                                 \
  target void name##_force(int begin, int end, const int64_t* row, const int32_t* nbr, const uint8_t* cls,          \
                           const double* l0, const float* w, const double* a, const double* bcoef, double v2,        \
                           const double* pos, const double* vel, double eta_over_e, double* force) {                \
    if (vel && cls)                                                                                                 \
      force_rows<true, false>(begin, end, row, nbr, cls, l0, w, a, bcoef, v2, pos, vel, eta_over_e, force);         \
    else if (cls)                                                                                                   \
      force_rows<false, false>(begin, end, row, nbr, cls, l0, w, a, bcoef, v2, pos, vel, eta_over_e, force);        \
    else if (vel)                                                                                                   \
      force_rows<true, true>(begin, end, row, nbr, cls, l0, w, a, bcoef, v2, pos, vel, eta_over_e, force);          \
    else                                                                                                            \
      force_rows<false, true>(begin, end, row, nbr, cls, l0, w, a, bcoef, v2, pos, vel, eta_over_e, force);         \
  }

PERIFLEX_LPS_ROW_LOOPS(baseline, )
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
PERIFLEX_LPS_ROW_LOOPS(avx2, __attribute__((target("avx2,fma"))))
PERIFLEX_LPS_ROW_LOOPS(avx512, __attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma"))))
#endif
#undef PERIFLEX_LPS_ROW_LOOPS

// the widest loops the CPU runs, found once
const RowLoops& row_loops() {
  static const RowLoops chosen = [] {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512dq"))
      return RowLoops{avx512_dilatation, avx512_force};
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return RowLoops{avx2_dilatation, avx2_force};
#endif
    return RowLoops{baseline_dilatation, baseline_force};
  }();
  return chosen;
}

// set by set_state_based_avx512
std::atomic<bool> wide_loops{true};
bool lps_wide_loops_allowed() { return wide_loops.load(std::memory_order_relaxed); }

#ifdef PERIFLEX_HAVE_LPS_AVX512
// true when the AVX-512 row loops may run on this body: the CPU has them, at most 16 length
// classes (a body off the grid has none), and no kernels narrower than AVX-512 were asked for (tests compare against them)
bool use_avx512(const BondStore& bonds) {
  static const bool cpu = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                          __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  return cpu && lps_wide_loops_allowed() && !bonds.own_lengths() && bonds.inv_length_table.size() <= 16;
}
#endif

// W_i of rows [begin, end) into out
void energy_rows(int begin, int end, const BondStore& bonds, const BondState& live, const LpsFields& lps,
                 const double* pos,
                 double* out) {
  for (int i = begin; i < end; ++i) {
    const double m = lps.weighted_volume[i];
    if (!(m > 0.0)) {
      out[i] = 0.0;
      continue;
    }
    // the dilatation first, then the deviatoric extensions e - theta |xi| / 2
    double sum = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double x0 = ref_length(bonds, b);
      sum += double(live.stiffness[b]) * x0 * (std::sqrt(dx * dx + dy * dy) - x0);
    }
    const double theta = 2.0 * lps.volume * sum / m;
    double dev = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double x0 = ref_length(bonds, b);
      const double ed = std::sqrt(dx * dx + dy * dy) - x0 - 0.5 * theta * x0;
      dev += double(live.stiffness[b]) * ed * ed;
    }
    out[i] = 0.5 * lps.kappa * theta * theta + 4.0 * lps.shear_modulus[i] / m * lps.volume * dev;
  }
}

}  // namespace

void set_state_based_avx512(bool enabled) { wide_loops = enabled; }

void refresh_weighted_volumes(const BondStore& bonds, const BondState& live, LpsFields& lps,
                              const std::vector<int>& particles) {
  for (int i : particles) {
    double sum = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const double x0 = ref_length(bonds, b);
      sum += double(live.stiffness[b]) * x0 * x0;
    }
    lps.weighted_volume[i] = lps.volume * sum;
    lps.shear_coef[i] = sum > 0.0 ? 8.0 * lps.shear_modulus[i] * lps.ratio(i) / lps.weighted_volume[i] : 0.0;
  }
}

void update_weighted_volumes(const BondStore& bonds, const BondState& live, LpsFields& lps) {
  const int n = bonds.particle_count();
  if (lps.shear_modulus.size() != static_cast<size_t>(n)) lps.shear_modulus.assign(n, lps.mu);
  lps.weighted_volume.assign(n, 0.0);
  lps.shear_coef.assign(n, 0.0);
  lps.bulk_coef.assign(n, 0.0);
  lps.dilatation.assign(n, 0.0);
  lps.records.assign(4 * static_cast<size_t>(n), 0.0);
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  refresh_weighted_volumes(bonds, live, lps, all);
}

void compute_dilatations(const BondStore& bonds, const BondState& live, LpsFields& lps, const double* pos) {
  const RowLoops& loops = row_loops();
  for_row_blocks(bonds.particle_count(), [&](int begin, int end) {
    loops.dilatation(begin, end, bonds.row.data(), bonds.neighbor.data(), cls_of(bonds),
                     l0_of(bonds), live.stiffness.data(), lps.weighted_volume.data(), lps.volume,
                     pos, lps.dilatation.data(), nullptr);
  });
}

void add_state_based_forces(const BondStore& bonds, const BondState& live, LpsFields& lps, const double* pos,
                            const double* vel, double eta_over_e, double* force, double* row_max, double* pos_copy) {
  const int n = bonds.particle_count();
  // a_i = (2 kappa - 4 mu_i) theta_i / m_i
  const double twice_kappa = 2.0 * lps.kappa;
  const double* mu = lps.shear_modulus.data();
  const RowLoops& loops = row_loops();
#ifdef PERIFLEX_HAVE_LPS_AVX512
  // the AVX-512 loops (undamped) when the CPU has them and the class tables fit two registers
  if (use_avx512(bonds) && !(eta_over_e > 0.0)) {
    const double v2 = lps.volume * lps.volume;
    for_row_blocks(n, [&](int begin, int end) {
      if (pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, pos_copy + 2 * begin);
      lps_extension_sums_avx512(begin, end, bonds, live, pos, lps.dilatation.data(), row_max);
      for (int i = begin; i < end; ++i) {
        const double m = lps.weighted_volume[i];
        lps.dilatation[i] = m > 0.0 ? 2.0 * lps.volume * lps.dilatation[i] / m : 0.0;
        lps.bulk_coef[i] = m > 0.0 ? (twice_kappa - 4.0 * mu[i]) * lps.dilatation[i] * lps.ratio(i) / m : 0.0;
        double* record = lps.records.data() + 4 * static_cast<int64_t>(i);
        record[0] = pos[2 * i];
        record[1] = pos[2 * i + 1];
        record[2] = lps.bulk_coef[i];
        record[3] = lps.shear_coef[i];
      }
    });
    for_row_blocks(n, [&](int begin, int end) {
      lps_forces_avx512(begin, end, bonds, live, lps.records.data(), v2, force);
    });
    return;
  }
#endif
  // pass 1: dilatations (and the row maxima of the stretch), then a_i = (2 kappa - 4 mu) theta_i / m_i
  for_row_blocks(n, [&](int begin, int end) {
    if (pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, pos_copy + 2 * begin);
    loops.dilatation(begin, end, bonds.row.data(), bonds.neighbor.data(), cls_of(bonds),
                     l0_of(bonds), live.stiffness.data(), lps.weighted_volume.data(), lps.volume,
                     pos, lps.dilatation.data(), row_max);
    for (int i = begin; i < end; ++i) {
      const double m = lps.weighted_volume[i];
      lps.bulk_coef[i] = m > 0.0 ? (twice_kappa - 4.0 * mu[i]) * lps.dilatation[i] * lps.ratio(i) / m : 0.0;
    }
  });
  // pass 2: pair forces, which need a_j of every neighbour, so only after pass 1 has finished
  const double v2 = lps.volume * lps.volume;
  for_row_blocks(n, [&](int begin, int end) {
    loops.force(begin, end, bonds.row.data(), bonds.neighbor.data(), cls_of(bonds),
                l0_of(bonds), live.stiffness.data(), lps.bulk_coef.data(), lps.shear_coef.data(),
                v2, pos, eta_over_e > 0.0 ? vel : nullptr, eta_over_e, force);
  });
}

void state_based_energy_density(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                                double* out) {
  for_row_blocks(bonds.particle_count(), [&](int begin, int end) { energy_rows(begin, end, bonds, live, lps, pos,
                 out); });
}

double state_based_strain_energy(const BondStore& bonds, const BondState& live, const LpsFields& lps,
                                 const double* pos) {
  // rows summed in fixed ranges and the ranges in order: the same bits on any thread count
  std::vector<double> density(bonds.particle_count());
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    energy_rows(static_cast<int>(begin), static_cast<int>(end), bonds, live, lps, pos, density.data());
    double sum = 0.0;
    for (int64_t i = begin; i < end; ++i) sum += density[i] * lps.ratio(static_cast<int>(i));
    return lps.volume * sum;
  });
}

double state_based_rows_energy(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                               const std::vector<int>& particles) {
  double sum = 0.0;
  std::vector<double> density(bonds.particle_count());
  for (int i : particles) {
    energy_rows(i, i + 1, bonds, live, lps, pos, density.data());
    sum += density[i] * lps.ratio(i);
  }
  return lps.volume * sum;
}

double state_based_damping_power(const BondStore& bonds, const BondState& live, const LpsFields& lps, const double* pos,
                                 const double* vel, double eta_over_e) {
  // each pair is visited from both ends: half per visit
  const double v2 = lps.volume * lps.volume;
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int i = static_cast<int>(begin); i < static_cast<int>(end); ++i) {
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const int32_t j = bonds.neighbor[b];
        const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
        const double rate = (dx * (vel[2 * j] - vel[2 * i]) + dy * (vel[2 * j + 1] - vel[2 * i + 1])) /
                            std::sqrt(dx * dx + dy * dy);
        sum += 0.5 * v2 * double(live.stiffness[b]) * (lps.shear_coef[i] + lps.shear_coef[j]) * eta_over_e *
               rate * rate;
      }
    }
    return sum;
  });
}

double state_based_critical_time_step(const BondStore& bonds, const BondState& live, const LpsFields& lps,
                                      const std::vector<double>& masses) {
  // A_i / m_i per particle, A_i = max(2 kappa, 4 mu_i)
  std::vector<double> ratio(bonds.particle_count(), 0.0);
  for (int i = 0; i < bonds.particle_count(); ++i)
    if (lps.weighted_volume[i] > 0.0)
      ratio[i] = std::max(2.0 * lps.kappa, 4.0 * lps.shear_modulus[i]) * lps.ratio(i) / lps.weighted_volume[i];
  const double v2 = lps.volume * lps.volume;
  double dt = std::numeric_limits<double>::infinity();
  for (int i = 0; i < bonds.particle_count(); ++i) {
    const double mi = lps.weighted_volume[i];
    double sum = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const double mj = lps.weighted_volume[bonds.neighbor[b]];
      if (!(mi > 0.0) || !(mj > 0.0)) continue;
      // k / |xi| of the bounding pair bond
      sum += 2.0 * double(live.stiffness[b]) * v2 * (ratio[i] + ratio[bonds.neighbor[b]]);
    }
    if (sum > 0.0) dt = std::min(dt, std::sqrt(2.0 * masses[i] / sum));
  }
  return dt;
}

}  // namespace periflex
