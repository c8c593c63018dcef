// The part of a flexible body that stepping changes, as a plain value (the rest of a
// Simulation's state is in solve/sim_state.h).
#pragma once

#include <cstdint>
#include <vector>

namespace periflex {

// One flexible body: which bonds broke and what follows from them.
struct FlexState {
  std::vector<uint64_t> broken_bits;    // one bit per stored bond direction (BondStore order)
  long broken_pairs = 0;
  long pending_broken = 0;              // broken by evaluations, not yet reported (0 between steps)
  double pending_energy = 0.0;
  // state-based bodies: the weighted volumes and shear coefficients over the intact bonds
  std::vector<double> weighted_volume, shear_coef;
  // bilinear-softening bodies: the largest stretch each stored bond direction has reached past s0
  std::vector<double> bond_history;
};

}  // namespace periflex
