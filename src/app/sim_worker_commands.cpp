// How the simulation thread applies each request of the user interface (app/sim_command.h):
// between two steps, in the order they were sent, one handler per type of request.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "app/sim_worker.h"

namespace periflex {

namespace {

std::string describe_speed(double speed) {
  if (speed <= 0.0) return "as fast as possible";
  char text[48];
  std::snprintf(text, sizeof text, "%gx real time", speed);
  return text;
}

std::string describe_settings(const LiveSettings& s) {
  static const char* methods[] = {"none", "baumgarte", "projection"};
  char text[256];
  std::snprintf(text, sizeof text,
                "integrator=%s dt=%g correction=%s alpha=%g beta=%g tolerance=%g bond_damping=%g "
                "global_damping=%g fracture=%s%s",
                s.integrator.c_str(), s.dt, methods[static_cast<int>(s.correction.method)],
                s.correction.alpha, s.correction.beta, s.correction.tolerance, s.bond_damping,
                s.global_damping, s.fracture ? "on" : "off", s.allow_unstable ? " (dt past the stable step allowed)" : "");
  return text;
}

}  // namespace

bool SimWorker::refused_after_failure(const char* verb, const std::string& by) {
  if (!numerical_error_) return false;
  log_.add(std::string("cannot ") + verb + ": the last step failed; reset, reload or change a setting first" + by);
  return true;
}

void SimWorker::start_running(const std::string& by) {
  running_ = true;
  pending_steps_ = 0;
  reanchor();
  log_.add("run, " + describe_speed(speed_) + by);
}

void SimWorker::settings_accepted() {
  numerical_error_.reset();
  numerical_message_.clear();
  rejected_key_.clear();
  rejected_message_.clear();
}

template <>
void SimWorker::handle(command::Run&, const std::string& by) {
  leave_scrub(("run" + by).c_str());
  if (refused_after_failure("run", by)) return;
  start_running(by);
}

template <>
void SimWorker::handle(command::Pause&, const std::string& by) {
  running_ = false;
  pending_steps_ = 0;
  log_.add("pause at t = " + std::to_string(run_->time()) + by);
}

template <>
void SimWorker::handle(command::ToggleRun&, const std::string& by) {
  if (running_) {
    running_ = false;
    log_.add("pause at t = " + std::to_string(run_->time()) + by);
    return;
  }
  command::Run run;
  handle(run, by);
}

template <>
void SimWorker::handle(command::Step& step, const std::string& by) {
  if (refused_after_failure("step", by)) return;
  leave_scrub(("step" + by).c_str());
  running_ = false;
  const int steps = step.steps > 0 ? step.steps : 1;
  pending_steps_ += steps;
  log_.add("step x" + std::to_string(steps) + by);
}

template <>
void SimWorker::handle(command::StepTo& step_to, const std::string& by) {
  if (refused_after_failure("step", by)) return;
  leave_scrub(("step to t" + by).c_str());
  running_ = false;
  // whole steps of dt from now, the last one at or after the time asked (a step of dt
  // that would overshoot it by less than a billionth of dt is not taken)
  const double dt = run_->settings().dt;
  const double remaining = step_to.time - run_->time();
  const double steps = dt > 0.0 && remaining > 0.0 ? std::ceil(remaining / dt - 1e-9) : 0.0;
  pending_steps_ = static_cast<int>(std::min(steps, 2e9));
  log_.add("step to t = " + std::to_string(step_to.time) + ": " + std::to_string(pending_steps_) + " steps" + by);
}

template <>
void SimWorker::handle(command::Reset&, const std::string& by) {
  try {
    // the model puts back the state it started in; one that cannot is built again
    if (run_->reset_to_start())
      restarted(scene_.name, ("reset" + by).c_str());
    else
      rebuild(scene_, true, ("reset" + by).c_str());
  } catch (const std::exception& e) {
    log_.add("reset failed, keeping the current model: " + std::string(e.what()));
  }
}

template <>
void SimWorker::handle(command::Reload&, const std::string& by) {
  load_from_disk(scene_path_, overrides_, ("reload of " + scene_path_ + by).c_str());
}

template <>
void SimWorker::handle(command::LoadScene& load, const std::string& by) {
  // overrides given on the command line belong to the first scene only
  load_from_disk(load.path, {}, ("switch to " + load.path + by).c_str());
}

template <>
void SimWorker::handle(command::ApplySettings& apply, const std::string& by) {
  try {
    run_->apply(apply.settings);
    settings_accepted();
    log_.add("settings: " + describe_settings(run_->settings()) + by);
  } catch (const std::exception& e) {
    note_rejection(e);
    log_.add("settings rejected: " + std::string(e.what()) + by);
  }
}

template <>
void SimWorker::handle(command::SetParameter& set, const std::string& by) {
  LiveSettings s = run_->settings();
  const std::string what = "set " + set.key + "=" + set.value;
  const std::string problem = set_live_parameter(s, set.key, set.value);
  if (!problem.empty()) {
    rejected_key_ = set.key;
    rejected_message_ = problem;
    log_.add(what + " rejected: " + problem + by);
    return;
  }
  try {
    run_->apply(s);
    settings_accepted();
    log_.add(what + by);
  } catch (const std::exception& e) {
    note_rejection(e);
    log_.add(what + " rejected: " + e.what() + by);
  }
}

template <>
void SimWorker::handle(command::SetSpeed& speed, const std::string& by) {
  speed_ = speed.factor;
  reanchor();
  log_.add("speed " + describe_speed(speed_) + by);
}

template <>
void SimWorker::handle(command::MouseSpring& mouse, const std::string& by) {
  mouse_stiffness_ = run_->set_mouse_spring(mouse.spring);
  // dragging sends a request per frame: log only grabbing and releasing
  if (!mouse.spring) {
    log_.add("mouse spring released" + by);
  } else if (mouse.new_grab) {
    log_.add(mouse.spring->body >= 0 ? "grab body " + std::to_string(mouse.spring->body) + by
                                     : "grab particle " + std::to_string(mouse.spring->particle) + by);
  }
}

template <>
void SimWorker::handle(command::Reactions& reactions, const std::string&) {
  run_->set_reactions(reactions.with_reactions);
}

template <>
void SimWorker::handle(command::Cut& cut, const std::string& by) {
  // paused or running, between two steps; a cut into a state shown changes its future
  leave_scrub(("knife" + by).c_str());
  const long count = run_->cut_bonds(cut.from, cut.to, cut.drawn_x, cut.drawn_y);
  log_.add("knife: " + std::to_string(count) + (count == 1 ? " bond cut" : " bonds cut") + by);
}

template <>
void SimWorker::handle(command::Record& record, const std::string& by) {
  record_interval_ = record.interval > 0.0 ? record.interval : 0.0;
  record_start_ = run_->time();
  record_marks_ = 0;
  log_.add(record_interval_ > 0.0 ? "recording every " + std::to_string(record_interval_) + " s" + by
                                  : "recording stopped" + by);
  // the first frame is the state at the moment recording starts
  record_if_due();
}

template <>
void SimWorker::handle(command::History& history, const std::string& by) {
  // the user's cadence and budget hold for every scene from now on
  history_auto_ = false;
  const size_t budget = static_cast<size_t>(std::max(1, history.budget_mb)) << 20;
  history_.configure(history.interval, budget, run_->time());
  log_.add((history_.interval() > 0.0 ? "history: a state every " + std::to_string(history_.interval()) + " s"
                                      : std::string("history: off")) +
           ", budget " + std::to_string(budget >> 20) + " MB" + by);
  if (scrub_ < 0 && history_.due(run_->time())) save_history_if_due();
}

template <>
void SimWorker::handle(command::Scrub& scrub, const std::string& by) {
  if (!keep_live(by)) return;
  const size_t index = history_.nearest(scrub.time);
  if (static_cast<long>(index) != scrub_) scrub_to(index, by);
}

template <>
void SimWorker::handle(command::ScrubStep& step, const std::string& by) {
  scrub_step(step.direction == command::ScrubStep::Direction::kBack ? -1 : 1, by);
}

template <>
void SimWorker::handle(command::Resume&, const std::string& by) {
  if (numerical_error_) {
    log_.add("cannot run: the last step failed; go back in the history, reset or change a setting first" + by);
    return;
  }
  leave_scrub(("resume" + by).c_str());
  start_running(by);
}

// the simulation thread's loop ends on Quit before applying it
template <>
void SimWorker::handle(command::Quit&, const std::string&) {}

void SimWorker::apply(SimCommand& c) {
  ++applied_;
  const std::string by = " (" + c.origin + ")";
  std::visit([&](auto& action) { handle(action, by); }, c.action);
}

}  // namespace periflex
