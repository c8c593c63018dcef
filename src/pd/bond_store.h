// Bonds of a peridynamic body as structure-of-arrays in compressed-row form. Every bond is
// stored once per direction (i -> j in row i, j -> i in row j) so each particle gathers its
// own force without atomics; both copies hold bit-identical data and therefore compute the
// same stretch and break together.
//
// The store is the model's: built once with the body and never written after. What breaking
// changes (each bond's live stiffness, its broken flag) is the body's state, BondState
// (bond_state.h), whose stiffness starts as a copy of the coefficients here.
//
// The force loop streams these arrays every step, so a stored direction holds only what it
// must: the neighbour as an offset j - i (2 bytes; the int32 index stays beside it for everything
// else), the stiffness (from BondState) in single precision (4 bytes: a relative rounding of 6e-8 of a material
// constant, the same for both copies, so forces stay equal and opposite) and the squared grid
// offset di^2 + dj^2 (1 byte), from which the reference length follows exactly as
// grid_spacing sqrt(di^2 + dj^2). A reference length itself stays in double precision: rounding it
// would pre-strain every bond. A body whose particles are off the grid (a point file of any
// layout, a jittered body) has no classes: each stored direction keeps its own 1 / |xi|
// (bond_inv_length, 8 bytes more a direction), the same bits in both copies.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace periflex {

struct BondStore {
  std::vector<int64_t> row;            // size n + 1: bonds of particle i are [row[i], row[i+1])
  std::vector<int32_t> neighbor;       // j of each bond
  std::vector<int16_t> neighbor_offset;  // j - i of each bond; empty when some |j - i| > 32767
  std::vector<uint8_t> length_class;   // di^2 + dj^2 of the grid offset from i to j (<= 255)
  // the law's coefficient of each intact stored direction (bond-based: k = c w(|xi|) beta g V_i V_j
  // [N], pair force = k s; the LPS: the weight w beta V_i V_j / V^2)
  std::vector<float> coefficient;
  double grid_spacing = 1.0;
  std::vector<double> inv_length_table;  // 1 / |xi| per length class (index = di^2 + dj^2)
  std::vector<double> bond_inv_length;   // 1 / |xi| of each stored direction off the grid; empty on it
  // materials by block (pd/block_materials.h): each particle's critical stretch (a bond breaks past
  // the smaller of its ends') and each row's smallest bond threshold; both empty: one s0 for all
  std::vector<double> particle_s0, row_s0;

  int particle_count() const { return row.empty() ? 0 : static_cast<int>(row.size() - 1); }
  int64_t directed_count() const { return static_cast<int64_t>(neighbor.size()); }
  // true when each stored direction keeps its own reference length (particles off the grid)
  bool own_lengths() const { return !bond_inv_length.empty(); }
  // 1 / |xi| of stored direction b.
  double inv_length(int64_t b) const {
    return own_lengths() ? bond_inv_length[b] : inv_length_table[length_class[b]];
  }
  // true when the critical stretch differs from particle to particle
  bool own_break_stretches() const { return !particle_s0.empty(); }
  // The critical stretch of stored direction b from particle i (s0 when there is one for all).
  double break_stretch(int i, int64_t b, double s0) const {
    return own_break_stretches() ? std::min(particle_s0[i], particle_s0[neighbor[b]]) : s0;
  }
  // The stretch below which no bond of row i breaks.
  double row_break_stretch(int i, double s0) const { return own_break_stretches() ? row_s0[i] : s0; }
  // Fills inv_length_table for every class up to the largest stored one.
  void make_length_table() {
    uint8_t largest = 0;
    for (uint8_t c : length_class) largest = c > largest ? c : largest;
    inv_length_table.assign(static_cast<size_t>(largest) + 1, 0.0);
    for (size_t c = 1; c < inv_length_table.size(); ++c)
      inv_length_table[c] = 1.0 / (grid_spacing * std::sqrt(static_cast<double>(c)));
  }
  // Fills neighbor_offset when every offset fits 16 bits (grids up to about 10,000 particles
  // across at a horizon of 3 spacings), else leaves it empty.
  void make_offsets() {
    neighbor_offset.clear();
    for (int i = 0; i < particle_count(); ++i)
      for (int64_t b = row[i]; b < row[i + 1]; ++b)
        if (neighbor[b] - i > 32767 || neighbor[b] - i < -32767) return;
    neighbor_offset.resize(neighbor.size());
    for (int i = 0; i < particle_count(); ++i)
      for (int64_t b = row[i]; b < row[i + 1]; ++b) neighbor_offset[b] = static_cast<int16_t>(neighbor[b] - i);
  }
  // Heap bytes held by the bond arrays and row offsets.
  size_t bytes() const {
    return row.capacity() * sizeof(int64_t) + neighbor.capacity() * sizeof(int32_t) +
           neighbor_offset.capacity() * sizeof(int16_t) + length_class.capacity() * sizeof(uint8_t) +
           coefficient.capacity() * sizeof(float) + inv_length_table.capacity() * sizeof(double) +
           bond_inv_length.capacity() * sizeof(double) +
           (particle_s0.capacity() + row_s0.capacity()) * sizeof(double);
  }
};

}  // namespace periflex
