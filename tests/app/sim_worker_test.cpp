// The simulation thread: requests are applied between steps in the order sent, stepping
// follows run/pause/step, pacing never runs ahead of wall time, and failures pause the run
// (numerical) or keep the old scene (bad file) instead of escaping the thread.
#include "app/sim_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"

namespace periflex {
namespace {

using namespace std::chrono_literals;

// What the fake records; written by the simulation thread only, read after stop() joins it.
struct FakeLog {
  std::vector<std::string> events;
  long applied_during_step = 0;
  std::thread::id step_thread, apply_thread;
  bool threads_differ = false;
  long saves = 0, restores = 0;   // of the whole state (the history)
};

class FakeModel final : public SteppedRun {
 public:
  FakeModel(FakeLog& log, double dt, double end_time, long fail_at_step)
      : log_(log), end_time_(end_time), fail_at_step_(fail_at_step) {
    settings_.dt = dt;
    settings_.integrator = "fake";
  }
  void step() override {
    in_step_ = true;
    if (log_.step_thread == std::thread::id()) log_.step_thread = std::this_thread::get_id();
    if (log_.step_thread != std::this_thread::get_id()) log_.threads_differ = true;
    if (fail_at_step_ >= 0 && steps_ + 1 >= fail_at_step_) {
      in_step_ = false;
      NumericalDiagnostic d;
      d.quantity = "kinetic energy";
      d.step = steps_ + 1;
      d.time = time_;
      d.cause = "test failure";
      d.remedy = "none";
      throw NumericalError(d);
    }
    // a little work, so requests have a chance to arrive while a step is under way
    volatile double x = 0.0;
    for (int i = 0; i < 200; ++i) x = x + i;
    time_ += settings_.dt;
    ++steps_;
    log_.events.push_back("step");
    in_step_ = false;
  }
  double time() const override { return time_; }
  long step_count() const override { return steps_; }
  double end_time() const override { return end_time_; }
  const ModelInfo& info() const override { return info_; }
  void fill_snapshot(Snapshot& out) const override {
    out.time = time_;
    out.step = steps_;
  }
  LiveSettings settings() const override { return settings_; }
  void apply(const LiveSettings& s) override {
    if (in_step_) ++log_.applied_during_step;
    log_.apply_thread = std::this_thread::get_id();
    if (log_.step_thread != std::thread::id() && log_.apply_thread != log_.step_thread) {
      log_.threads_differ = true;
    }
    settings_ = s;
    log_.events.push_back("apply " + std::to_string(static_cast<long>(s.bond_damping)));
  }
  double set_mouse_spring(const std::optional<MouseSpring>&) override { return 0.0; }
  bool save_state(SimState& out) const override {
    ++log_.saves;
    out.time = time_;
    out.steps = steps_;
    return true;
  }
  bool restore_state(const SimState& in) override {
    ++log_.restores;
    time_ = in.time;
    steps_ = in.steps;
    return true;
  }

 private:
  FakeLog& log_;
  LiveSettings settings_;
  ModelInfo info_;
  double time_ = 0.0;
  long steps_ = 0;
  double end_time_;
  long fail_at_step_;
  bool in_step_ = false;
};

// Scenes are named by path; "bad.toml" fails to load as a malformed file would.
RunFactory fake_factory(FakeLog& log, double dt, double end_time = 1e9, long fail_at_step = -1) {
  RunFactory f;
  f.load = [](const std::string& path, const std::vector<std::string>&) {
    if (path == "bad.toml") throw InputError({path, 3, 1, "bodies.crank.mass"}, "mass must be positive");
    SceneDef s;
    s.name = path;
    s.path = path;
    return s;
  };
  f.build = [&log, dt, end_time, fail_at_step](const SceneDef&) -> std::unique_ptr<SteppedRun> {
    return std::make_unique<FakeModel>(log, dt, end_time, fail_at_step);
  };
  return f;
}

// Polls the worker's status until `done` holds or a generous timeout passes.
bool wait_until(const SimWorker& worker, const std::function<bool(const WorkerStatus&)>& done) {
  const auto give_up = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < give_up) {
    if (done(worker.status())) return true;
    std::this_thread::sleep_for(1ms);
  }
  return false;
}

SimCommand set_bond_damping(long value) {
  SimCommand c{command::SetParameter{"bond_damping", std::to_string(value)}, "test"};
  return c;
}

// Sends two requests one after the other and waits until each is applied: between the two the
// worker has gone once round its loop (requests, then a step when one is due), so a step it was
// still to take has been taken when this returns. (A setting, not a pause: a pause would clear
// the steps still asked for and hide one too many.)
void wait_two_rounds(SimWorker& worker) {
  for (int round = 0; round < 2; ++round) {
    const long before = worker.status().commands_applied;
    worker.send(set_bond_damping(0));
    ASSERT_TRUE(wait_until(worker, [before](const WorkerStatus& s) { return s.commands_applied > before; }));
  }
}

TEST(SimWorker, RequestsApplyBetweenStepsInTheOrderSent) {
  FakeLog log;
  EventLog events(false);
  constexpr long kRequests = 300;
  {
    SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
    worker.start(true, 0.0);  // as fast as possible, so steps and requests interleave
    for (long i = 1; i <= kRequests; ++i) {
      worker.send(set_bond_damping(i));
      if (i % 50 == 0) std::this_thread::sleep_for(1ms);
    }
    // the start itself counts as no request; all kRequests must be applied
    ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.commands_applied >= kRequests; }));
    worker.stop();
  }
  // the applies are in order, none lost, none inside a step, all on the stepping thread
  long expected = 1, steps_between = 0;
  for (const std::string& e : log.events) {
    if (e == "step") {
      ++steps_between;
      continue;
    }
    EXPECT_EQ(e, "apply " + std::to_string(expected));
    ++expected;
  }
  EXPECT_EQ(expected, kRequests + 1);
  EXPECT_EQ(log.applied_during_step, 0);
  EXPECT_FALSE(log.threads_differ);
  EXPECT_GT(steps_between, 0);
}

TEST(SimWorker, PausedWorkerTakesExactlyTheStepsAsked) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  SimCommand step{command::Step{5}, "test"};
  worker.send(step);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 5; }));
  // paused again after the five: no further steps happen
  wait_two_rounds(worker);
  EXPECT_EQ(worker.status().step, 5);
  EXPECT_FALSE(worker.status().running);
  // the render side sees the snapshot of step 5
  ASSERT_TRUE(worker.update_snapshot());
  EXPECT_EQ(worker.snapshot().step, 5);
  EXPECT_NEAR(worker.snapshot().time, 5e-3, 1e-15);  // five sums of 1e-3: rounding only
  worker.stop();
}

TEST(SimWorker, StepToTimeStopsAtTheFirstStepAtOrAfterIt) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 3e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  // 0.1 s is 33.3 steps of 3 ms: the 34th is the first at or after it
  SimCommand to{command::StepTo{0.1}, "test"};
  worker.send(to);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 34; }));
  wait_two_rounds(worker);
  EXPECT_EQ(worker.status().step, 34);
  EXPECT_FALSE(worker.status().running);
  // a time already passed takes no step; a whole number of steps lands on it
  std::get<command::StepTo>(to.action).time = 0.05;
  worker.send(to);
  std::get<command::StepTo>(to.action).time = 34 * 3e-3 + 6e-3;
  worker.send(to);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 36; }));
  wait_two_rounds(worker);
  EXPECT_EQ(worker.status().step, 36);
  worker.stop();
}

TEST(SimWorker, RefusedSettingIsReportedWithItsKeyUntilOneIsAccepted) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  SimCommand bad{command::SetParameter{"dt", "-1"}, "test"};
  worker.send(bad);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return !s.rejected_message.empty(); }));
  EXPECT_EQ(worker.status().rejected_key, "dt");
  SimCommand good = bad;
  std::get<command::SetParameter>(good.action).value = "2e-3";
  worker.send(good);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.rejected_message.empty(); }));
  EXPECT_EQ(worker.status().settings.dt, 2e-3);
  worker.stop();
}

TEST(SimWorker, PacedRunNeverGetsAheadOfWallTime) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  constexpr double kSpeed = 0.1;
  const auto start = std::chrono::steady_clock::now();
  worker.start(true, kSpeed);
  std::this_thread::sleep_for(200ms);
  const WorkerStatus s = worker.status();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  worker.stop();
  // the worker may be at most one step ahead of speed x elapsed wall time
  EXPECT_LE(s.time, kSpeed * wall + 1e-3);
  EXPECT_TRUE(s.running);
}

TEST(SimWorker, NumericalFailurePausesAndReportsUntilReset) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3, 1e9, 10), "a.toml", {}, events);
  worker.start(true, 0.0);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.numerical_error.has_value(); }));
  WorkerStatus s = worker.status();
  EXPECT_FALSE(s.running);
  EXPECT_EQ(s.step, 9);  // the tenth step threw
  EXPECT_EQ(s.numerical_error->quantity, "kinetic energy");
  EXPECT_NE(s.numerical_message.find("kinetic energy"), std::string::npos);
  // run is refused while the failure stands
  worker.send(SimCommand{command::Run{}, "test"});
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& st) { return st.commands_applied >= 1; }));
  EXPECT_FALSE(worker.status().running);
  // reset clears it and starts again from t = 0
  worker.send(SimCommand{command::Reset{}, "test"});
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& st) { return st.commands_applied >= 2; }));
  s = worker.status();
  EXPECT_FALSE(s.numerical_error.has_value());
  EXPECT_EQ(s.step, 0);
  EXPECT_EQ(s.generation, 1);
  worker.stop();
}

TEST(SimWorker, BadReloadKeepsTheCurrentSceneAndSaysWhy) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  SimCommand load{command::LoadScene{"bad.toml"}, "test"};
  worker.send(load);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.commands_applied >= 1; }));
  WorkerStatus s = worker.status();
  EXPECT_EQ(s.scene_path, "a.toml");
  EXPECT_EQ(s.scene_generation, 1);
  EXPECT_NE(s.load_error.find("mass must be positive"), std::string::npos);
  // a good switch afterwards clears the message
  std::get<command::LoadScene>(load.action).path = "b.toml";
  worker.send(load);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& st) { return st.commands_applied >= 2; }));
  s = worker.status();
  EXPECT_EQ(s.scene_path, "b.toml");
  EXPECT_EQ(s.scene_generation, 2);
  EXPECT_TRUE(s.load_error.empty());
  worker.stop();
}

TEST(SimWorker, EndTimePausesTheRunOnce) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3, 0.02), "a.toml", {}, events);
  worker.start(true, 0.0);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return !s.running; }));
  // 0.02 s reached after twenty 1e-3 steps, give or take one for rounding of the sum
  EXPECT_NEAR(worker.status().step, 20, 1);
  worker.stop();
}

TEST(SimWorker, RecordingPublishesOneFramePerSimulatedInterval) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  SimCommand rec{command::Record{4e-3}, "test"};
  worker.send(rec);
  SimCommand step{command::Step{6}, "test"};
  worker.send(step);
  // frames at the start (step 0) and then every 4e-3 s: steps 0 and 4 of the six
  std::vector<long> steps;
  const auto give_up = std::chrono::steady_clock::now() + 20s;
  Snapshot frame;
  while (steps.size() < 2 && std::chrono::steady_clock::now() < give_up) {
    if (worker.take_recorded(frame)) steps.push_back(frame.step);
    else std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0], 0);
  EXPECT_EQ(steps[1], 4);
  worker.stop();
}

TEST(SimWorker, RecordingGoesOnFromTheStartAfterReset) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 1.0);
  SimCommand step{command::Step{3}, "test"};
  worker.send(step);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 3; }));
  SimCommand rec{command::Record{2e-3}, "test"};
  worker.send(rec);  // first frame at step 3
  worker.send(SimCommand{command::Reset{}, "test"});  // then one at step 0
  std::get<command::Step>(step.action).steps = 2;
  worker.send(step);  // and one at step 2
  std::vector<long> steps;
  const auto give_up = std::chrono::steady_clock::now() + 20s;
  Snapshot frame;
  while (steps.size() < 3 && std::chrono::steady_clock::now() < give_up) {
    if (worker.take_recorded(frame)) steps.push_back(frame.step);
    else std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(steps, (std::vector<long>{3, 0, 2}));
  worker.stop();
}

// The history's cadence off costs no solver time: not one state is taken while stepping. On,
// a state is taken at each mark.
TEST(SimWorker, HistoryOffTakesNoStateWhileStepping) {
  const auto saves_over = [](double interval) {
    FakeLog log;
    EventLog events(false);
    {
      SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
      worker.start(false, 0.0);
      SimCommand history{command::History{interval, 64}, "test"};
      worker.send(history);
      SimCommand step{command::Step{5000}, "test"};
      worker.send(step);
      EXPECT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 5000; }));
      EXPECT_EQ(worker.status().history_interval, interval);
      worker.stop();
    }
    return log.saves;
  };
  // the start state, taken when the worker starts under the scene's own cadence, and nothing after
  EXPECT_EQ(saves_over(0.0), 1);
  // marks at 0.01, ..., 5.0 besides the start (kept already at the mark at 0)
  EXPECT_EQ(saves_over(0.01), 1 + 500);
}

// Left steps back through the states kept, Right forward, a time picks the nearest state; all
// paused. Resuming drops the states after the one shown and runs from it.
TEST(SimWorker, ScrubbingShowsKeptStatesAndResumeDropsTheFuture) {
  FakeLog log;
  EventLog events(false);
  SimWorker worker(fake_factory(log, 1e-3), "a.toml", {}, events);
  worker.start(false, 0.0);
  SimCommand history{command::History{0.1, 64}, "test"};
  worker.send(history);
  SimCommand step{command::Step{1050}, "test"};
  worker.send(step);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 1050; }));
  // 0, 0.1, ..., 1.0: eleven states
  EXPECT_EQ(worker.status().history_states, 11u);
  SimCommand back{command::ScrubStep{command::ScrubStep::Direction::kBack}, "test"};
  for (int k = 0; k < 3; ++k) worker.send(back);
  // the live state (1.05) kept, then three back: 0.8
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.scrub >= 0 && s.step == 800; }));
  EXPECT_EQ(worker.status().history_states, 12u);
  EXPECT_FALSE(worker.status().running);
  SimCommand forward{command::ScrubStep{command::ScrubStep::Direction::kForward}, "test"};
  worker.send(forward);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 900; }));
  SimCommand to{command::Scrub{0.42}, "test"};
  worker.send(to);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 400; }));
  EXPECT_NEAR(worker.status().time, 0.4, 1e-12);
  // forward to the end comes back to the live state
  for (int k = 0; k < 20; ++k) worker.send(forward);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 1050; }));
  worker.send(to);
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.step == 400; }));
  // resumed: the states after 0.4 are gone, and the run goes on from step 400
  worker.send(SimCommand{command::Resume{}, "test"});
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return s.scrub < 0 && s.running; }));
  worker.send(SimCommand{command::Pause{}, "test"});
  ASSERT_TRUE(wait_until(worker, [](const WorkerStatus& s) { return !s.running; }));
  const WorkerStatus s = worker.status();
  EXPECT_GE(s.step, 400);
  EXPECT_LE(s.history_last, s.time);
  EXPECT_EQ(s.history_states, 5u + static_cast<size_t>((s.time + 1e-9) / 0.1) - 4u);
  worker.stop();
}

TEST(LiveParameter, ParsesKnownKeysAndRejectsBadValues) {
  LiveSettings s;
  s.dt = 1e-3;
  EXPECT_EQ(set_live_parameter(s, "bond_damping", "0.1"), "");
  EXPECT_DOUBLE_EQ(s.bond_damping, 0.1);
  EXPECT_EQ(set_live_parameter(s, "fracture", "off"), "");
  EXPECT_FALSE(s.fracture);
  EXPECT_EQ(set_live_parameter(s, "correction", "projection"), "");
  EXPECT_EQ(s.correction.method, CorrectionDef::Method::kProjection);
  EXPECT_EQ(set_live_parameter(s, "integrator", "rk4"), "");
  EXPECT_EQ(s.integrator, "rk4");
  // bad values leave the settings as they were
  EXPECT_NE(set_live_parameter(s, "dt", "0"), "");
  EXPECT_NE(set_live_parameter(s, "dt", "fast"), "");
  EXPECT_NE(set_live_parameter(s, "alpha", "-1"), "");
  EXPECT_NE(set_live_parameter(s, "colour", "red"), "");
  EXPECT_DOUBLE_EQ(s.dt, 1e-3);
}

}  // namespace
}  // namespace periflex
