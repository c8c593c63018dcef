// One source of the elastic bond row loop in xsimd; PERIFLEX_XSIMD_SUFFIX names the instruction set
// this translation unit is compiled for (bench/CMakeLists.txt builds it once per set). Same
// formula as the portable loop in src/pd/bond_kernel.cpp: k (1/|xi| - 1/|y|) y.
#include <xsimd/xsimd.hpp>

#include "pd_simd_library_rows.h"

#define PERIFLEX_JOIN2(a, b) a##b
#define PERIFLEX_JOIN(a, b) PERIFLEX_JOIN2(a, b)

namespace periflex::bench {

namespace {

using Batch = xsimd::batch<double>;
constexpr int kLanes = static_cast<int>(Batch::size);

// Lanes past the row's end take the particle itself with k = 0 and 1/|xi| = 0, and r2 = 1: no force.
template <bool kGather>
inline void rows(int begin, int end, const RowArrays& r, const double* pos, double* force) {
  alignas(64) double xj[kLanes], yj[kLanes], l0[kLanes], k[kLanes];
  alignas(64) int64_t twice_j[kLanes];
  for (int i = begin; i < end; ++i) {
    const Batch xi(pos[2 * i]), yi(pos[2 * i + 1]);
    Batch ax(0.0), ay(0.0);
    const int64_t last = r.row[i + 1];
    for (int64_t b = r.row[i]; b < last; b += kLanes) {
      const int64_t left = last - b;
      Batch x, y;
      if (left >= kLanes) {
        // a full block: the lanes without tests
        for (int q = 0; q < kLanes; ++q) {
          l0[q] = r.l0[r.cls[b + q]];
          k[q] = double(r.k[b + q]);
          if constexpr (kGather) {
            twice_j[q] = 2 * static_cast<int64_t>(r.nbr[b + q]);
          } else {
            xj[q] = pos[2 * r.nbr[b + q]];
            yj[q] = pos[2 * r.nbr[b + q] + 1];
          }
        }
      } else {
      for (int q = 0; q < kLanes; ++q) {
        const bool on = q < left;
        l0[q] = on ? r.l0[r.cls[b + q]] : 0.0;
        k[q] = on ? double(r.k[b + q]) : 0.0;
        if constexpr (kGather) {
          twice_j[q] = 2 * static_cast<int64_t>(on ? r.nbr[b + q] : i);
        } else {
          const int32_t j = on ? r.nbr[b + q] : i;
          xj[q] = pos[2 * j];
          yj[q] = pos[2 * j + 1];
        }
      }
      }
      if constexpr (kGather) {
        const auto idx = xsimd::batch<int64_t>::load_aligned(twice_j);
        x = Batch::gather(pos, idx);
        y = Batch::gather(pos + 1, idx);
      } else {
        x = Batch::load_aligned(xj);
        y = Batch::load_aligned(yj);
      }
      const Batch dx = x - xi, dy = y - yi, inv0 = Batch::load_aligned(l0);
      const Batch r2 = xsimd::select(inv0 > Batch(0.0), xsimd::fma(dx, dx, dy * dy), Batch(1.0));
      const Batch inv_len = Batch(1.0) / xsimd::sqrt(r2);
      const Batch f = Batch::load_aligned(k) * (inv0 - inv_len);
      ax = xsimd::fma(f, dx, ax);
      ay = xsimd::fma(f, dy, ay);
    }
    force[2 * i] += xsimd::hadd(ax);
    force[2 * i + 1] += xsimd::hadd(ay);
  }
}

}  // namespace

void PERIFLEX_JOIN(elastic_rows_xsimd_, PERIFLEX_XSIMD_SUFFIX)(int begin, int end, const RowArrays& r, const double* pos,
                                                               double* force) {
  rows<false>(begin, end, r, pos, force);
}

void PERIFLEX_JOIN(elastic_rows_xsimd_gather_, PERIFLEX_XSIMD_SUFFIX)(int begin, int end, const RowArrays& r,
                                                                      const double* pos, double* force) {
  rows<true>(begin, end, r, pos, force);
}

}  // namespace periflex::bench
