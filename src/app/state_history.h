// The window's history: a ring of simulation states saved at a simulated-time cadence, within a
// memory budget, for scrubbing back and resuming (MuJoCo's simulate keeps such a history).
//
//   StateHistory h;
//   h.configure(0.01, 256 << 20, sim.time());       // a state every 0.01 s, at most 256 MB
//   ... after every step:
//   if (h.due(sim.time())) { SimState s; sim.save_state(s); h.add(std::move(s), sim.time(), steps); }
//   ... to go back:
//   SimState s; h.get(h.nearest(0.5), s); sim.restore_state(s);
//
// States are saved at the first step at or after each mark origin + k interval (marks counted,
// not summed, so an interval that does not divide dt does not drift). Off (interval 0) costs one
// comparison per step and nothing else. When the budget is exceeded, the oldest half of the ring
// is thinned (every other state there dropped, the first one kept), so the recent past stays dense
// and the far past sparser instead of refusing new states. Large states are kept compressed
// (output/state_codec.h and deflate) when the budget
// would hold few of them, small ones as they are. Owned by the simulation thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "solve/sim_state.h"

namespace periflex {

// States larger than the budget over this are kept compressed: the budget would hold fewer
// than this many of them as they are. Compressing takes ten or more times a copy and saves a
// quarter to a third of the bytes (docs/gui.md), worth it only where the budget binds.
constexpr size_t kCompressBelowStates = 64;

class StateHistory {
 public:
  // Saves every `interval` simulated seconds (<= 0: off) within `budget` bytes, marks counted
  // from `now`; states already kept stay (thinned at once if the budget shrank).
  void configure(double interval, size_t budget, double now);
  double interval() const { return interval_; }
  size_t budget() const { return budget_; }
  // States of at least `bytes` are kept compressed (0: budget / kCompressBelowStates).
  void compress_from(size_t bytes) { compress_from_ = bytes; }

  // Whether the state at `time` is to be saved (always false when off).
  bool due(double time) const { return interval_ > 0.0 && time + 1e-9 * interval_ >= mark(marks_); }
  // Keeps `state` (of simulated time `time`, step `step`) and moves the marks past it; thins the
  // ring when over budget. A state no later than the newest kept is not kept twice. A state larger than the whole budget is
  // not kept (too_large() says so).
  void add(SimState&& state, double time, long step);
  // Moves the marks past `time` without keeping a state (one is kept at that instant already).
  void pass(double time);
  // Whether a state at or after `time` is kept.
  bool has(double time) const { return !entries_.empty() && time <= entries_.back().time; }
  // Forgets every state; marks counted from `origin` (a reset or a new scene).
  void clear(double origin);
  // Forgets the states after entry `index` (the future of a resumed state); the next mark is
  // the first after that entry's time.
  void drop_after(size_t index);

  size_t size() const { return entries_.size(); }
  double time(size_t index) const { return entries_[index].time; }
  long step(size_t index) const { return entries_[index].step; }
  // The entry whose time is nearest `time` (size() must be > 0).
  size_t nearest(double time) const;
  // The state of entry `index` (decompressed when kept compressed).
  void get(size_t index, SimState& out) const;

  // Bytes the kept states take, and whether the last one added is kept compressed.
  size_t bytes() const { return bytes_; }
  bool compressed() const { return compressed_; }
  // The last state offered was larger than the whole budget and not kept.
  bool too_large() const { return too_large_; }

 private:
  struct Entry {
    double time = 0.0;
    long step = 0;
    SimState state;                // when kept as it is
    std::vector<uint8_t> packed;   // when kept compressed: deflate of encode_state's bytes
    size_t raw_size = 0;           // encode_state's byte count, for decompressing
    size_t bytes = 0;              // what the entry holds
  };
  double mark(long k) const { return origin_ + static_cast<double>(k) * interval_; }
  void thin();

  std::vector<Entry> entries_;
  double interval_ = 0.0;
  size_t budget_ = 0;
  double origin_ = 0.0;
  long marks_ = 0;        // marks already passed
  size_t bytes_ = 0;
  bool compressed_ = false;
  bool too_large_ = false;
  size_t compress_from_ = 0;
};

}  // namespace periflex
