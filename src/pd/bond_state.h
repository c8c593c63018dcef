// The live part of a peridynamic body's bonds: what breaking changes. The bond topology and each
// bond's coefficient stay in the body's BondStore (the model's, never written after the build);
// here each stored direction has the stiffness the loops multiply by (the coefficient while
// intact, 0 once broken: the force loops need no branch) and its broken flag.
//
// Saving keeps one bit per stored direction; restoring sets both arrays from those bits and the
// store's coefficients, whatever broke since: a restore needs no record of what broke.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pd/bond_store.h"

namespace periflex {

struct BondState {
  std::vector<float> stiffness;  // per stored direction: BondStore::coefficient, 0 once broken
  // per stored direction: 0 intact, 1 broken; 2 while a force evaluation that left it out has not
  // settled it yet (bond_kernel.h)
  std::vector<uint8_t> broken;

  // Every bond of `bonds` intact.
  static BondState intact(const BondStore& bonds);
  // The broken flags as bits, 64 stored directions to a word (bit k % 64 of word k / 64).
  void save_bits(std::vector<uint64_t>& bits) const;
  // Sets the flags to `bits` (as save_bits wrote them for bonds of the same store) and each
  // stiffness to the coefficient or 0. Words already equal are skipped: before fracture this
  // reads the flags alone.
  void restore_bits(const BondStore& bonds, const std::vector<uint64_t>& bits);
  // Breaks stored direction b: stiffness 0, flag 1.
  void break_bond(int64_t b) {
    stiffness[b] = 0.0f;
    broken[b] = 1;
  }
  size_t bytes() const { return stiffness.capacity() * sizeof(float) + broken.capacity(); }
};

}  // namespace periflex
