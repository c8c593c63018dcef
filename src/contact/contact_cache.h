// The part of a contact that stepping changes, as a plain value (the rest of a Simulation's
// state is in solve/sim_state.h).
#pragma once

#include <cstdint>
#include <vector>

namespace periflex {

// A particle contact's Verlet list and where it was built: which pairs its sums visit, and in
// what order, depends on it.
struct ContactCache {
  std::vector<int64_t> row;
  std::vector<int32_t> col;
  std::vector<double> built_at;
  long built_broken = -1;  // kept in the format; written as 0 and not read (bonded pairs are in the list)
};

}  // namespace periflex
