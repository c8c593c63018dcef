#include "solve/balance_drift.h"

#include <cmath>

namespace periflex {

void BalanceDrift::record(double time, double balance) {
  time_[next_] = time;
  balance_[next_] = balance;
  next_ = (next_ + 1) % kSamples;
  if (count_ < kSamples) ++count_;
}

double BalanceDrift::change_over(double span) const {
  if (count_ < 2) return 0.0;
  const int newest = (next_ + kSamples - 1) % kSamples;
  // walk back to the first sample at least `span` older than the newest (or the oldest kept)
  int back = newest;
  for (int k = 1; k < count_; ++k) {
    back = (newest + kSamples - k) % kSamples;
    if (time_[newest] - time_[back] >= span) break;
  }
  const double elapsed = time_[newest] - time_[back];
  if (!(elapsed > 0.0)) return 0.0;
  // the net change at the rate of that stretch: an error that oscillates step by step counts by
  // what it moves the balance, not by the sum of its swings
  return std::abs(balance_[newest] - balance_[back]) * span / elapsed;
}

void BalanceDrift::samples(std::vector<double>& times, std::vector<double>& balances) const {
  times.clear();
  balances.clear();
  for (int k = 0; k < count_; ++k) {
    const int at = (next_ + kSamples - count_ + k) % kSamples;
    times.push_back(time_[at]);
    balances.push_back(balance_[at]);
  }
}

}  // namespace periflex
