// Simulated time: one answer to "have we reached t?" for everything that asks it (the solver's
// advance, the run loop's end, rows, frames and snapshots), and a clock that multiplies instead
// of adding, so a long run does not drift off the times it is asked to land on.
#pragma once

#include <cfloat>
#include <cmath>

namespace periflex {

// Two times closer than this count as the same instant: a billionth of a step, or a few dozen
// units in the last place of the time itself once t / dt is so large that the first is below
// round-off (a run of 1e7 steps and more).
inline double time_tolerance(double dt, double t) { return 1e-9 * dt + 64.0 * DBL_EPSILON * std::abs(t); }

// True when `now` is at `target` or past it, within time_tolerance.
inline bool time_reached(double now, double target, double dt) {
  return now >= target - time_tolerance(dt, target);
}

// The clock of a run: time = origin + steps * dt. The origin moves only where a step was
// shortened to land on a requested time (which is then exact) or where dt changes, so the time
// after n plain steps carries one rounding, not n.
class SimClock {
 public:
  double time() const { return origin_ + static_cast<double>(steps_) * dt_; }
  double dt() const { return dt_; }

  // Starts at t with steps of dt.
  void reset(double t, double dt) {
    origin_ = t;
    dt_ = dt;
    steps_ = 0;
  }
  // A new step size from the current time on.
  void set_dt(double dt) { reset(time(), dt); }
  // The time after one more plain step (not yet taken).
  double next_time() const { return origin_ + static_cast<double>(steps_ + 1) * dt_; }
  // One plain step was taken.
  void tick() { ++steps_; }
  // A step landed exactly on t.
  void land(double t) { reset(t, dt_); }
  // The parts of the clock, for saving and restoring it exactly.
  double origin() const { return origin_; }
  long steps() const { return steps_; }
  void restore(double origin, double dt, long steps) {
    origin_ = origin;
    dt_ = dt;
    steps_ = steps;
  }

 private:
  double origin_ = 0.0;
  double dt_ = 0.0;
  long steps_ = 0;
};

}  // namespace periflex
