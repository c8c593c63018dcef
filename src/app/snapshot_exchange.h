// Hands the latest complete snapshot from the simulation thread to the render thread
// without either ever waiting for the other (a triple buffer).
//
//   writer (simulation thread)        reader (render thread)
//     Snapshot& s = ex.back();          if (ex.update()) { ... a newer one arrived ... }
//     sim.fill_snapshot(s);             const Snapshot& s = ex.front();  // draw it
//     ex.publish();
//
// Three slots: the writer owns one (back), the reader owns one (front), and the third
// (middle) holds the newest published value. publish() swaps back and middle; update()
// swaps middle and front when the middle is newer. Each swap is one atomic exchange, so
// the reader always holds a slot the writer finished and will not touch until handed back.
// No GL here: the unit tests run without a display.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace periflex {

template <class T>
class SnapshotExchange {
 public:
  SnapshotExchange() = default;
  SnapshotExchange(const SnapshotExchange&) = delete;
  SnapshotExchange& operator=(const SnapshotExchange&) = delete;

  // Writer side: the slot to fill next. Its previous contents are an older value, so
  // containers in it keep their capacity and refilling does not allocate.
  T& back() { return slots_[back_]; }
  // Writer side: make back() the newest value and take another slot to fill.
  void publish() {
    const uint32_t old = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel);
    back_ = old & kIndexMask;
  }

  // Reader side: take the newest published value if there is one not yet seen.
  // Returns true when front() changed.
  bool update() {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const uint32_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndexMask;
    seen_ = true;
    return true;
  }
  // Reader side: the value taken by the last update() (a default T before the first).
  const T& front() const { return slots_[front_]; }
  // Reader side: true once update() has taken at least one published value.
  bool has_front() const { return seen_; }

 private:
  static constexpr uint32_t kFresh = 4;      // set in middle_ by publish, cleared by update
  static constexpr uint32_t kIndexMask = 3;

  std::array<T, 3> slots_{};
  uint32_t back_ = 0;                    // touched by the writer only
  uint32_t front_ = 2;                   // touched by the reader only
  bool seen_ = false;                    // reader only
  std::atomic<uint32_t> middle_{1};
};

}  // namespace periflex
