#include "pd/bond_state.h"

#include <algorithm>

#include "core/parallel_chunks.h"

namespace periflex {

BondState BondState::intact(const BondStore& bonds) {
  BondState state;
  state.stiffness = bonds.coefficient;
  state.broken.assign(bonds.coefficient.size(), 0);
  return state;
}

void BondState::save_bits(std::vector<uint64_t>& bits) const {
  const int64_t count = static_cast<int64_t>(broken.size());
  bits.assign(static_cast<size_t>((count + 63) / 64), 0);
  uint64_t* out = bits.data();
  const uint8_t* flags = broken.data();
  parallel_chunks(static_cast<int64_t>(bits.size()), [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t w = begin; w < end; ++w) {
      uint64_t word = 0;
      const int64_t last = std::min<int64_t>(64, count - 64 * w);
      for (int64_t k = 0; k < last; ++k) word |= static_cast<uint64_t>(flags[64 * w + k] != 0) << k;
      out[w] = word;
    }
  });
}

void BondState::restore_bits(const BondStore& bonds, const std::vector<uint64_t>& bits) {
  const int64_t count = static_cast<int64_t>(broken.size());
  const uint64_t* in = bits.data();
  parallel_chunks(static_cast<int64_t>(bits.size()), [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t w = begin; w < end; ++w) {
      const int64_t first = 64 * w, last = std::min<int64_t>(first + 64, count);
      bool same = true;
      for (int64_t k = first; k < last && same; ++k) same = (broken[k] != 0) == (((in[w] >> (k - first)) & 1u) != 0);
      if (same) continue;
      for (int64_t k = first; k < last; ++k) {
        const bool is_broken = ((in[w] >> (k - first)) & 1u) != 0;
        broken[k] = is_broken ? 1 : 0;
        stiffness[k] = is_broken ? 0.0f : bonds.coefficient[k];
      }
    }
  });
}

}  // namespace periflex
