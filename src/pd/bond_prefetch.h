// Asks the memory for the bond arrays some rows ahead of the row loops (bond-based and
// state-based, AVX-512). Every stored direction's neighbour offset, length class and weight are
// streamed once per pass (7 bytes), and the loops waited on those loads: the hardware prefetcher
// alone did not keep up. On the 64,000-particle plate of bench/pd_state_based_bench.cpp the
// state-based forces took about 1.5x less time with this and the bond-based 1.3x less
// (docs/peridynamics.md, state-based speed).
#pragma once

#include <cstdint>

namespace periflex {

// How far ahead of the current row's end: 160 bonds, about six interior rows at a horizon of
// three spacings.
constexpr int64_t kPrefetchAheadBonds = 160;

// element k of array, formed as an integer: past the array's end a prefetch is harmless, but a
// pointer formed there would not be
template <typename T>
inline void prefetch_element(const T* array, int64_t k) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<uintptr_t>(array) + sizeof(T) * k));
}

// The lines of the bonds kPrefetchAheadBonds past bond b: two of the weights (an interior row holds
// 112 bytes of them), one of the classes and one of the neighbours (offsets or indices), as many as
// a row reads; the hardware prefetcher keeps up with the rest.
template <typename Neighbor>
inline void prefetch_bonds_ahead(const float* weight, const uint8_t* length_class, const Neighbor* neighbor,
                                 int64_t b) {
  const int64_t k = b + kPrefetchAheadBonds;
  prefetch_element(weight, k);
  prefetch_element(weight, k + 16);
  prefetch_element(length_class, k);
  prefetch_element(neighbor, k);
}

}  // namespace periflex
