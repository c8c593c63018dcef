// Size of a state, for the window's memory budget.
#include "solve/sim_state.h"

namespace periflex {

size_t state_bytes(const SimState& s) {
  size_t bytes = sizeof(SimState);
  bytes += sizeof(double) * static_cast<size_t>(s.q.size() + s.qd.size());
  bytes += sizeof(int) * (s.passage.rows.size() + s.rank.dropped.size() + s.rank.last_dependent.size());
  bytes += sizeof(double) * s.integrator.scalars.size();
  for (const auto& v : s.integrator.vectors) bytes += sizeof(double) * static_cast<size_t>(v.size());
  for (const auto& f : s.flex) {
    bytes += sizeof(FlexState) + sizeof(uint64_t) * f.broken_bits.size();
    bytes += sizeof(double) * (f.weighted_volume.size() + f.shear_coef.size() + f.bond_history.size());
  }
  for (const auto& c : s.contacts) {
    bytes += sizeof(ContactCache) + sizeof(int64_t) * c.row.size() + sizeof(int32_t) * c.col.size() +
             sizeof(double) * c.built_at.size();
  }
  return bytes;
}

}  // namespace periflex
