// How fast the integrator's own energy error moves where nothing singular happens.
//
// The energy balance of a run is not zero: each integrator has an error of its own, O(dt^p) and
// changing with the motion (for symplectic Euler with projection on the IFToMM A02 double
// four-bar at dt = 2.5e-4, about 1e-3 J in the 0.04 s a dead point takes). A passage through a
// singular position is judged against it: the balance may move across the passage by what it
// moved over as long a span just before, not by a fixed share of the energy. The record keeps
// the last kSamples (time, balance) pairs taken outside passages, in a fixed ring (no
// allocation while stepping).
//
//   drift.record(t, balance);                  // after each step outside a passage
//   double expected = drift.change_over(0.04); // |balance change| over 0.04 s at the recent rate
#pragma once

#include <array>
#include <vector>

namespace periflex {

class BalanceDrift {
 public:
  static constexpr int kSamples = 64;

  // Forgets every sample (after a passage: the span before the next one is measured afresh).
  void clear() { count_ = next_ = 0; }
  // Adds the balance after a step (times increasing).
  void record(double time, double balance);
  // The change of the balance the recent samples show over `span` seconds: the change from the
  // newest sample back to the newest one at least `span` older, scaled to `span`; when the
  // samples do not reach that far back, the mean rate over all of them times `span`. 0 with
  // fewer than two samples.
  double change_over(double span) const;
  int size() const { return count_; }
  // The samples, oldest first: recording them again in this order into a cleared record gives
  // the same record (checkpoints keep them this way).
  void samples(std::vector<double>& times, std::vector<double>& balances) const;

 private:
  std::array<double, kSamples> time_{}, balance_{};
  int count_ = 0, next_ = 0;
};

}  // namespace periflex
