#include "pd/bond_kernel.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "core/parallel_chunks.h"
#include "pd/row_blocks.h"
#include "pd/bond_rows.h"

// The portable row loops live here; bond_rows_avx2.cpp and bond_rows_avx512.cpp hold the vector
// ones. The portable loops stay scalar-ish: std::sqrt may set errno, which keeps GCC from
// vectorising it without -fno-math-errno, a flag the build does not set.

namespace periflex {

namespace {

// k (1/|xi| - 1/|y|) y = k s y/|y|: one square root and one division per bond, no branch
// (a broken bond has k = 0). With kTrack the largest stretch over the row's intact bonds
// (at most 0 when none) goes to most[i] as a by-product.
template <bool kTrack, bool kOwn>
void elastic_rows(int begin, int end, const Rows& r, const double* __restrict pos, double* __restrict force,
                  double* __restrict most, const RowCut* cut) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double fx = 0.0, fy = 0.0, top = -1.0;
#pragma omp simd reduction(+ : fx, fy) reduction(max : top)
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
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

// as elastic_rows, plus k eta/E ds/dt with ds/dt = e . (v_j - v_i) / |xi|, along e
template <bool kTrack, bool kOwn>
void damped_rows(int begin, int end, const Rows& r, const double* __restrict pos, const double* __restrict vel,
                 double eta_over_e, double* __restrict force, double* __restrict most, const RowCut* cut) {
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

// largest stretch over the intact bonds (k > 0) of each row; -1 for a row without any
template <bool kOwn>
void row_max_stretch(int begin, int end, const Rows& r, const double* __restrict pos, double* __restrict out) {
  for (int i = begin; i < end; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double most = -1.0;
#pragma omp simd reduction(max : most)
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double s = std::sqrt(dx * dx + dy * dy) * (kOwn ? r.own[b] : r.l0[r.cls[b]]) - 1.0;
      most = std::max(most, r.k[b] > 0.0f ? s : -1.0);
    }
    out[i] = most;
  }
}


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

// The row loops for these bonds: the AVX-512 ones read the class table from registers and test
// every row against one s0, so a body off the grid (its own length per bond) or of several
// materials (its own s0 per particle) takes the AVX2 ones at most.
Isa isa(const BondStore& bonds) {
  return bonds.own_lengths() || bonds.own_break_stretches() ? std::min(isa(), Isa::kAvx2) : isa();
}

// the stretch of bond b of particle i, computed the same way for both of its copies
inline double stretch(const BondStore& bonds, const double* pos, int i, int64_t b) {
  const int32_t j = bonds.neighbor[b];
  const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
  return std::sqrt(dx * dx + dy * dy) * bonds.inv_length(b) - 1.0;
}

// Largest stretch of each row into out.
void row_maxima(const BondStore& bonds, const BondState& live, const double* pos, double* out) {
  const Rows r = rows_of(bonds, live);
  const Isa which = isa(bonds);
  for_row_blocks(bonds.particle_count(), [&](int begin, int end) {
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
    if (which == Isa::kAvx512) return row_max_stretch_avx512(begin, end, r, pos, out);
#endif
    if (r.own)
      row_max_stretch<true>(begin, end, r, pos, out);
    else
      row_max_stretch<false>(begin, end, r, pos, out);
  });
}

// A quarter of k |xi| s^2 summed over rows [begin, end), row by row in order; the reference length
// from the class table or each bond's own (chosen once for the rows, not per bond).
template <bool kOwn>
double strain_energy_rows(int begin, int end, const Rows& r, const double* pos) {
  double sum = 0.0;
  for (int i = begin; i < end; ++i) {
    double local = 0.0;
    for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
      const int32_t j = r.nbr[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double l0 = kOwn ? r.own[b] : r.l0[r.cls[b]];
      const double s = std::sqrt(dx * dx + dy * dy) * l0 - 1.0;
      local += double(r.k[b]) * s * s / l0;
    }
    sum += 0.25 * local;
  }
  return sum;
}

// Rows [begin, end) of the portable elastic (vel null) or damped force loop.
template <bool kOwn>
void portable_rows(int begin, int end, bool track, const Rows& r, const double* pos, const double* vel,
                   double eta_over_e, double* force, double* row_max, const RowCut* cut) {
  if (vel) {
    if (track) return damped_rows<true, kOwn>(begin, end, r, pos, vel, eta_over_e, force, row_max, cut);
    return damped_rows<false, kOwn>(begin, end, r, pos, vel, eta_over_e, force, row_max, cut);
  }
  if (track) return elastic_rows<true, kOwn>(begin, end, r, pos, force, row_max, cut);
  elastic_rows<false, kOwn>(begin, end, r, pos, force, row_max, cut);
}

// Rows [begin, end) of the elastic (vel null) or damped force loop the CPU runs best.
void force_rows(int begin, int end, Isa which, const Rows& r, const double* pos, const double* vel,
                double eta_over_e, double* force, double* row_max, const RowCut* cut) {
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
  if (vel) {
    if (which == Isa::kAvx512) return damped_rows_avx512(begin, end, r, pos, vel, eta_over_e, force, row_max, cut);
    if (which == Isa::kAvx2) return damped_rows_avx2(begin, end, r, pos, vel, eta_over_e, force, row_max, cut);
  } else {
    if (which == Isa::kAvx512) return elastic_rows_avx512(begin, end, r, pos, force, row_max, cut);
    if (which == Isa::kAvx2) return elastic_rows_avx2(begin, end, r, pos, force, row_max, cut);
  }
#else
  (void)which;
#endif
  const bool track = row_max || cut;
  if (r.own) return portable_rows<true>(begin, end, track, r, pos, vel, eta_over_e, force, row_max, cut);
  portable_rows<false>(begin, end, track, r, pos, vel, eta_over_e, force, row_max, cut);
}

// The whole force loop, chunk by chunk on the threads; pos_copy receives pos chunk by chunk.
void force_loop(const BondStore& bonds, const BondState& live, const double* pos, const double* vel, double eta_over_e,
                double* force, double* row_max, double* pos_copy, const RowCut* cut) {
  const Rows r = rows_of(bonds, live);
  const Isa which = isa(bonds);
  for_row_blocks(bonds.particle_count(), [&](int begin, int end) {
    if (pos_copy) std::copy(pos + 2 * begin, pos + 2 * end, pos_copy + 2 * begin);
    force_rows(begin, end, which, r, pos, vel, eta_over_e, force, row_max, cut);
  });
}

}  // namespace

void cut_row_forces(int i, const Rows& r, const RowCut& cut, const double* pos, const double* vel,
                    double eta_over_e, double& fx, double& fy) {
  const bool fixed = cut.no_fail && cut.no_fail[i];
  bool left_out = false;
  for (int64_t b = r.row[i]; b < r.row[i + 1]; ++b) {
    const int32_t j = r.nbr[b];
    const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
    const double len = std::sqrt(dx * dx + dy * dy);
    const double l0 = ref_inv_length(r, b), k = r.k[b];
    // the exact stretch, as stretch() below: the same bits in both copies of the bond
    if (k > 0.0 && !fixed && !(cut.no_fail && cut.no_fail[j]) && len * l0 - 1.0 > bond_threshold(r, cut, i, j)) {
      cut.broken[b] = 2;
      left_out = true;
      continue;
    }
    const double inv_len = 1.0 / len;
    double f = k * (l0 - inv_len);
    if (vel) {
      const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
      f = k * ((l0 - inv_len) + eta_over_e * ((dx * dvx + dy * dvy) * inv_len * l0) * inv_len);
    }
    fx += f * dx;
    fy += f * dy;
  }
  if (left_out) cut.row_broke[i] = 1;
}

void set_vector_kernels(VectorKernels widest) { widest_allowed = widest; }
void set_vector_kernels_enabled(bool enabled) { set_vector_kernels(enabled ? Isa::kAvx512 : Isa::kPortable); }

void add_bond_forces(const BondStore& bonds, const BondState& live, const double* pos, double* force, double* row_max,
                     double* pos_copy) {
  force_loop(bonds, live, pos, nullptr, 0.0, force, row_max, pos_copy, nullptr);
}

void add_damped_bond_forces(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                            double eta_over_e, double* force, double* row_max, double* pos_copy) {
  force_loop(bonds, live, pos, vel, eta_over_e, force, row_max, pos_copy, nullptr);
}

void add_bond_forces_breaking(const BondStore& bonds, BondState& live, const double* pos, const double* vel,
                              double eta_over_e, const BreakingEvaluation& breaking, double* force, double* pos_copy) {
  const RowCut cut{breaking.s0, breaking.no_fail, live.broken.data(), breaking.row_broke};
  force_loop(bonds, live, pos, vel && eta_over_e > 0.0 ? vel : nullptr, eta_over_e, force, nullptr, pos_copy, &cut);
}

long settle_broken_bonds(const BondStore& bonds, BondState& live, const double* pos, const double* vel,
                         double half_kick, uint8_t* row_broke, double& energy_released) {
  // in row order on one thread: the same sum on any thread count (only rows at a crack tip)
  long directed = 0;
  double energy = 0.0;
  const int n = bonds.particle_count();
  // the flagged rows are few: jump between them (a byte search) rather than test every row
  for (int i = 0; i < n; ++i) {
    i = static_cast<int>(std::find(row_broke + i, row_broke + n, uint8_t{1}) - row_broke);
    if (i == n) break;
    row_broke[i] = 0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (live.broken[b] != 2) continue;
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double len = std::sqrt(dx * dx + dy * dy), l0 = bonds.inv_length(b), k = live.stiffness[b];
      const double s = len * l0 - 1.0;
      // a quarter of k |xi| s^2 per copy: the strain energy where the evaluation saw the bond
      double e = 0.25 * k * s * s / l0;
      // less the work its force k s e would have done on the particles over the half-kick it
      // no longer takes part in: -(h/2) k s e . (v_j - v_i) per pair, half per copy
      if (half_kick > 0.0 && vel) {
        const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
        e -= 0.5 * half_kick * k * s * (dx * dvx + dy * dvy) / len;
      }
      energy += e;
      live.break_bond(b);
      ++directed;
    }
  }
  energy_released = energy;
  return directed / 2;
}

double bond_strain_energy(const BondStore& bonds, const BondState& live, const double* pos) {
  // each pair is visited twice: a quarter of k |xi| s^2 per visit; rows summed in fixed ranges
  // and the ranges in order, so the energy has the same bits on any thread count
  const Rows r = rows_of(bonds, live);
  const Isa which = isa(bonds);
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
#ifdef PERIFLEX_HAVE_VECTOR_KERNELS
    if (which == Isa::kAvx512 && strain_energy_avx512(static_cast<int>(begin), static_cast<int>(end), r, pos, sum))
      return sum;
#else
    (void)which;
#endif
    if (r.own) return strain_energy_rows<true>(static_cast<int>(begin), static_cast<int>(end), r, pos);
    return strain_energy_rows<false>(static_cast<int>(begin), static_cast<int>(end), r, pos);
  });
}

double bond_damping_power(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                          double eta_over_e) {
  // k eta/E |xi| (ds/dt)^2 per pair, half per visit; a fixed-order sum as above
  return ordered_sum(bonds.particle_count(), kRowParallelMin, [&](int64_t begin, int64_t end) {
    double sum = 0.0;
    for (int i = static_cast<int>(begin); i < static_cast<int>(end); ++i) {
      double local = 0.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const int32_t j = bonds.neighbor[b];
        const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
        const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
        const double l0 = bonds.inv_length(b);
        const double rate = (dx * dvx + dy * dvy) / std::sqrt(dx * dx + dy * dy) * l0;
        local += double(live.stiffness[b]) * eta_over_e * rate * rate / l0;
      }
      sum += 0.5 * local;
    }
    return sum;
  });
}

long break_stretched_bonds(const BondStore& bonds, BondState& live, const double* pos, double s0,
                           const uint8_t* no_fail, double& energy_released, const double* row_max) {
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
    row_maxima(bonds, live, pos, computed.data());
  }
  const double* most = row_max ? row_max : computed.data();
  for (int i = 0; i < n; ++i) {
    if (most[i] <= bonds.row_break_stretch(i, s0) - kCutSlack || (no_fail && no_fail[i])) continue;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (live.broken[b] || (no_fail && no_fail[bonds.neighbor[b]])) continue;
      const double s = stretch(bonds, pos, i, b);
      if (s > bonds.break_stretch(i, b, s0)) {
        energy += 0.25 * double(live.stiffness[b]) * s * s / bonds.inv_length(b);
        live.break_bond(b);
        ++directed;
      }
    }
  }
  energy_released = energy;
  return directed / 2;
}

void max_bond_stretch(const BondStore& bonds, const BondState& live, const double* pos, float* out) {
  const int n = bonds.particle_count();
  std::vector<double> most(n);
  row_maxima(bonds, live, pos, most.data());
  for (int i = 0; i < n; ++i) out[i] = static_cast<float>(std::max(most[i], 0.0));
}

}  // namespace periflex
