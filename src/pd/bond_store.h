// Bonds of a peridynamic body as structure-of-arrays in compressed-row form. Every bond is
// stored once per direction (i -> j in row i, j -> i in row j) so each particle gathers its
// own force without atomics; both copies hold bit-identical data and therefore compute the
// same stretch and break together.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace periflex {

struct BondStore {
  std::vector<int64_t> row;        // size n + 1: bonds of particle i are [row[i], row[i+1])
  std::vector<int32_t> neighbor;   // j of each bond
  std::vector<double> inv_length;  // 1 / |xi|, reference length from exact grid offsets
  std::vector<double> stiffness;   // k = c w(|xi|) beta g V_i V_j [N]: pair force = k s; 0 once broken
  std::vector<uint8_t> broken;     // 1 once broken (never heals)

  int particle_count() const { return row.empty() ? 0 : static_cast<int>(row.size() - 1); }
  int64_t directed_count() const { return static_cast<int64_t>(neighbor.size()); }
  // Heap bytes held by the bond arrays and row offsets.
  size_t bytes() const {
    return row.capacity() * sizeof(int64_t) + neighbor.capacity() * sizeof(int32_t) +
           inv_length.capacity() * sizeof(double) + stiffness.capacity() * sizeof(double) +
           broken.capacity() * sizeof(uint8_t);
  }
};

}  // namespace periflex
