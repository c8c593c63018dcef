// The simulation thread's history: states saved at the cadence, scrubbing back and forth
// through them (paused), and resuming from the one shown with the later ones dropped.
#include <algorithm>
#include <cstdio>

#include "app/sim_worker.h"

namespace periflex {

namespace {

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", t);
  return text;
}

}  // namespace

void SimWorker::history_defaults() {
  // a scene's own cadence: kDefaultHistoryStates over its end time (else every 1000 steps),
  // until the user sets one; the budget stays as set
  double interval = history_.interval();
  if (history_auto_) {
    const double end = run_->end_time();
    interval = end > 0.0 ? end / kDefaultHistoryStates : 1000.0 * run_->settings().dt;
  }
  const size_t budget = history_.budget() > 0 ? history_.budget() : kDefaultHistoryBudget;
  history_.configure(interval, budget, run_->time());
  history_.clear(run_->time());
  scrub_ = -1;
  if (history_.due(run_->time())) save_history_if_due();
}

void SimWorker::save_history_if_due() {
  // called only when due (the loop checks first, so a cadence of 0 costs one comparison); an
  // instant kept already is not taken twice
  if (history_.has(run_->time())) {
    history_.pass(run_->time());
    return;
  }
  SimState state;
  // a model that keeps no state: the marks move on all the same, so it is not asked every step
  if (!run_->save_state(state)) {
    history_.pass(run_->time());
    return;
  }
  history_.add(std::move(state), run_->time(), run_->step_count());
}

void SimWorker::scrub_to(size_t index, const std::string& by) {
  SimState state;
  history_.get(index, state);
  if (!run_->restore_state(state)) {
    log_.add("this model keeps no history" + by);
    return;
  }
  // shown paused, nothing held by the mouse, a failure after it forgotten
  scrub_ = static_cast<long>(index);
  running_ = false;
  pending_steps_ = 0;
  mouse_stiffness_ = run_->set_mouse_spring(std::nullopt);
  numerical_error_.reset();
  numerical_message_.clear();
  reanchor();
  // a recording goes on from the state shown once it runs again
  if (record_interval_ > 0.0) {
    record_start_ = run_->time();
    record_marks_ = 0;
  }
  log_.add("history: t = " + seconds(run_->time()) + " (state " + std::to_string(index + 1) + " of " +
           std::to_string(history_.size()) + ")" + by);
}

bool SimWorker::keep_live(const std::string& by) {
  // the live state is kept first, so scrubbing forward again comes back to it
  if (scrub_ < 0 && (history_.size() == 0 || run_->time() > history_.time(history_.size() - 1))) {
    save_history_if_due();
  }
  if (history_.size() == 0) log_.add("history: no states kept (cadence off or model without history)" + by);
  return history_.size() > 0;
}

void SimWorker::scrub_step(int direction, const std::string& by) {
  if (!keep_live(by)) return;
  const long from = scrub_ >= 0 ? scrub_ : static_cast<long>(history_.size()) - 1;
  const long to = std::clamp(from + direction, 0L, static_cast<long>(history_.size()) - 1);
  if (to == scrub_) return;
  scrub_to(static_cast<size_t>(to), by);
}

void SimWorker::leave_scrub(const char* why) {
  if (scrub_ < 0) return;
  // the states after the one shown belong to a future that is about to be recomputed
  const size_t dropped = history_.size() - static_cast<size_t>(scrub_) - 1;
  history_.drop_after(static_cast<size_t>(scrub_));
  scrub_ = -1;
  log_.add(std::string(why) + " from t = " + seconds(run_->time()) + ": " + std::to_string(dropped) +
           " later history states dropped");
}

}  // namespace periflex
