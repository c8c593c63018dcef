// A one-line progress bar on a terminal: fraction done, simulated time, steps per second, ETA.
// Silent when standard error is not a terminal or the run is quiet.
#pragma once

#include <chrono>
#include <string>

namespace periflex {

class ProgressBar {
 public:
  ProgressBar(double end_time, bool enabled);
  // Redraws at most ten times a second.
  void update(double time, long steps, const std::string& extra = "");
  // Clears the bar line.
  void finish();
  bool enabled() const { return enabled_; }

 private:
  using Clock = std::chrono::steady_clock;
  double end_time_;
  bool enabled_;
  Clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

bool stderr_is_terminal();

}  // namespace periflex
