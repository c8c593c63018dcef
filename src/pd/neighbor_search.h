// Fixed-radius neighbour search with a cell list: O(N) for particles of bounded density.
// The result is a compressed-row (CSR) list holding every pair in both directions, each
// row sorted by neighbour index, identical for any thread count.
#pragma once

#include <cstdint>
#include <vector>

namespace periflex {

struct NeighborList {
  std::vector<int64_t> row;       // size n + 1; neighbours of i are col[row[i] .. row[i+1])
  std::vector<int32_t> col;       // neighbour indices
};

// Every j != i with |p_j - p_i| <= radius. x and y hold n positions.
NeighborList find_neighbors(const std::vector<double>& x, const std::vector<double>& y, double radius);

}  // namespace periflex
