#include "app/sim_worker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "core/error.h"
#include "scene/file_shape_reader.h"
#include "scene/grid_scan.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

// how often a running simulation hands a snapshot to the render thread (wall seconds)
constexpr double kPublishInterval = 1.0 / 120.0;
// window over which steps/s and simulated s per wall s are measured
constexpr double kRateWindow = 0.5;
// a run more than this many wall seconds behind its pace drops the debt instead of bursting
constexpr double kMaxLag = 0.25;

}  // namespace

SimWorker::SimWorker(RunFactory factory, const std::string& scene_path,
                     std::vector<std::string> overrides, EventLog& log)
    : factory_(std::move(factory)), log_(log), scene_path_(scene_path), overrides_(std::move(overrides)) {
  // the first scene is loaded here so that run_gui can exit with code 2 before opening a window
  scene_ = factory_.load(scene_path_, overrides_);
  run_ = factory_.build(scene_);
  scene_generation_ = 1;
  log_.add("loaded scene '" + scene_.name + "' from " + scene_path_ +
           (scene_.solver.device == "gpu" ? ", bond forces on the GPU in " + scene_.solver.precision : ""));
  history_defaults();
  publish();
}

SimWorker::~SimWorker() { stop(); }

void SimWorker::start(bool run, double speed) {
  if (thread_.joinable()) return;
  running_ = run;
  speed_ = speed;
  reanchor();
  publish();
  thread_ = std::thread([this] { loop(); });
}

void SimWorker::stop() {
  if (!thread_.joinable()) return;
  {
    // under the lock, so a simulation thread about to wait for recording space sees it
    std::lock_guard<std::mutex> lock(record_mutex_);
    quitting_ = true;
  }
  send(SimCommand{command::Quit{}});
  record_space_.notify_all();
  thread_.join();
}

WorkerStatus SimWorker::status() const {
  std::lock_guard<std::mutex> lock(status_mutex_);
  return status_;
}

bool SimWorker::take_recorded(Snapshot& out) {
  std::lock_guard<std::mutex> lock(record_mutex_);
  if (recorded_.empty()) return false;
  out = std::move(recorded_.front());
  recorded_.pop_front();
  record_space_.notify_all();
  return true;
}

void SimWorker::reanchor() {
  anchor_wall_ = Clock::now();
  anchor_sim_ = run_->time();
  rate_wall_ = anchor_wall_;
  rate_steps_ = run_->step_count();
  rate_sim_ = run_->time();
}

void SimWorker::publish() {
  // the snapshot first, then the status that describes it
  run_->fill_snapshot(exchange_.back());
  exchange_.publish();
  WorkerStatus s;
  s.running = running_;
  s.time = run_->time();
  s.step = run_->step_count();
  s.end_time = run_->end_time();
  s.speed = speed_;
  s.steps_per_second = running_ ? steps_per_second_ : 0.0;
  s.sim_seconds_per_second = running_ ? sim_per_second_ : 0.0;
  s.settings = run_->settings();
  s.info = run_->info();
  s.scene_path = scene_path_;
  s.scene_name = scene_.name;
  s.scene_description = scene_.description;
  s.geometry_files.clear();
  s.geometry_summary.clear();
  for (const FlexBodyDef& flex : scene_.flex_bodies) {
    if (!geometry_file(flex).empty()) s.geometry_files.push_back(geometry_file(flex));
    Vec2 lo, hi;
    shape_bounds(flex.shape, lo, hi);
    s.geometry_summary.push_back("'" + flex.name + "': " +
                                 (flex.geometry_source.empty() ? std::string("shape of the scene") : flex.geometry_source) +
                                 ", x in [" + format_number(lo.x()) + ", " + format_number(hi.x()) + "] m, y in [" +
                                 format_number(lo.y()) + ", " + format_number(hi.y()) + "] m");
  }
  s.generation = generation_;
  s.scene_generation = scene_generation_;
  s.numerical_error = numerical_error_;
  s.numerical_message = numerical_message_;
  s.load_error = load_error_;
  s.commands_applied = applied_;
  s.recording = record_interval_ > 0.0;
  s.mouse_stiffness = mouse_stiffness_;
  s.rejected_key = rejected_key_;
  s.rejected_message = rejected_message_;
  s.history_interval = history_.interval();
  s.history_budget = history_.budget();
  s.history_bytes = history_.bytes();
  s.history_states = history_.size();
  s.history_first = history_.size() ? history_.time(0) : 0.0;
  s.history_last = history_.size() ? history_.time(history_.size() - 1) : 0.0;
  s.history_compressed = history_.compressed();
  s.history_too_large = history_.too_large();
  s.scrub = scrub_;
  std::lock_guard<std::mutex> lock(status_mutex_);
  status_ = std::move(s);
}

void SimWorker::note_rejection(const std::exception& e) {
  // the live setting a refusal names ("solver.dt" -> "dt"), for the panel to show it there
  const auto* input = dynamic_cast<const InputError*>(&e);
  rejected_key_ = input ? input->where().key : std::string();
  if (rejected_key_.rfind("solver.", 0) == 0) rejected_key_ = rejected_key_.substr(7);
  rejected_message_ = input ? input->detail() : std::string(e.what());
}

void SimWorker::rebuild(const SceneDef& scene, bool keep_settings, const char* what) {
  // build the new model completely before replacing the old one, so a failure keeps it
  const LiveSettings kept = run_->settings();
  std::unique_ptr<SteppedRun> fresh = factory_.build(scene);
  // live changes carry over; a model already on those settings is left alone
  if (keep_settings && !same_live_settings(kept, fresh->settings())) fresh->apply(kept);
  run_ = std::move(fresh);
  restarted(scene.name, what);
}

void SimWorker::restarted(const std::string& scene_name, const char* what) {
  mouse_stiffness_ = 0.0;  // a new or reset model holds nothing
  rejected_key_.clear();
  rejected_message_.clear();
  ++generation_;
  numerical_error_.reset();
  numerical_message_.clear();
  running_ = false;
  pending_steps_ = 0;
  reanchor();
  log_.add(std::string(what) + ": scene '" + scene_name + "' at t = 0, paused");
  // the history starts again with the new start
  history_defaults();
  // a recording goes on from the new start
  if (record_interval_ > 0.0) {
    record_start_ = run_->time();
    record_marks_ = 0;
    record_if_due();
  }
}

void SimWorker::load_from_disk(const std::string& path, const std::vector<std::string>& overrides,
                               const char* what) {
  try {
    SceneDef scene = factory_.load(path, overrides);
    rebuild(scene, false, what);
    scene_ = std::move(scene);
    scene_path_ = path;
    overrides_ = overrides;
    ++scene_generation_;
    load_error_.clear();
  } catch (const InputError& e) {
    load_error_ = e.what();
    log_.add(std::string(what) + " failed, keeping the current scene: " + e.what());
  } catch (const NumericalError& e) {
    load_error_ = e.what();
    log_.add(std::string(what) + " failed at initialisation, keeping the current scene: " + e.what());
  } catch (const std::exception& e) {
    load_error_ = e.what();
    log_.add(std::string(what) + " failed, keeping the current scene: " + e.what());
  }
}

void SimWorker::record_if_due() {
  // frames at fixed simulated times: the first step at or after each mark start + k interval
  // (marks counted, not summed, so they do not drift), one frame however many marks a step crosses
  const auto mark = [this](long k) { return record_start_ + static_cast<double>(k) * record_interval_; };
  const double now = run_->time() + 1e-9 * record_interval_;
  if (record_interval_ <= 0.0 || now < mark(record_marks_)) return;
  while (mark(record_marks_) <= now) ++record_marks_;
  Snapshot frame;
  run_->fill_snapshot(frame);
  std::unique_lock<std::mutex> lock(record_mutex_);
  record_space_.wait(lock, [this] { return recorded_.size() < kMaxRecorded || quitting_; });
  recorded_.push_back(std::move(frame));
}

void SimWorker::loop() {
  if (factory_.started) factory_.started();
  Clock::time_point last_publish = Clock::now();
  double publish_seconds = 0.0;  // what the last publish while stepping took
  for (;;) {
    // requests first: they land between two steps, in the order they were sent
    bool changed = false;
    for (SimCommand& c : commands_.drain()) {
      if (std::holds_alternative<command::Quit>(c.action)) return;
      apply(c);
      changed = true;
    }
    if (changed) publish();

    // paused: sleep until a request arrives
    if (!running_ && pending_steps_ == 0) {
      commands_.wait_for(std::chrono::milliseconds(50));
      continue;
    }

    // paced: wait while the simulation is ahead of wall time x speed
    if (running_ && speed_ > 0.0) {
      const double wall = std::chrono::duration<double>(Clock::now() - anchor_wall_).count();
      const double target = anchor_sim_ + speed_ * wall;
      if (run_->time() >= target) {
        const double ahead = (run_->time() - target) / speed_;
        commands_.wait_for(std::chrono::duration<double>(std::min(ahead, 0.01)));
        if (Clock::now() - last_publish > std::chrono::duration<double>(kPublishInterval)) {
          publish();
          last_publish = Clock::now();
        }
        continue;
      }
      if ((target - run_->time()) / speed_ > kMaxLag) {
        anchor_wall_ = Clock::now() - std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(kMaxLag));
        anchor_sim_ = run_->time();
      }
    }

    // one step; a numerical failure pauses the run and is shown, never thrown further
    const bool before_end = run_->end_time() > 0.0 && run_->time() < run_->end_time();
    try {
      run_->step();
    } catch (const NumericalError& e) {
      running_ = false;
      pending_steps_ = 0;
      numerical_error_ = e.diagnostic();
      numerical_message_ = e.what();
      log_.add(std::string("numerical failure, paused: ") + e.what());
      publish();
      continue;
    } catch (const std::exception& e) {
      running_ = false;
      pending_steps_ = 0;
      numerical_error_ = NumericalDiagnostic{"step", run_->step_count(), run_->time(), e.what(), ""};
      numerical_message_ = e.what();
      log_.add(std::string("step failed, paused: ") + e.what());
      publish();
      continue;
    }
    record_if_due();
    // the history: one comparison per step when its cadence is off
    if (history_.due(run_->time())) save_history_if_due();

    bool publish_now = false;
    if (pending_steps_ > 0 && --pending_steps_ == 0) publish_now = true;
    // the scene's end time pauses a run once; pressing run again continues past it
    if (running_ && before_end && run_->time() >= run_->end_time()) {
      running_ = false;
      publish_now = true;
      log_.add("reached the scene's end time t = " + std::to_string(run_->end_time()) + ", paused");
    }

    // rates over a sliding half second
    const Clock::time_point now = Clock::now();
    const double span = std::chrono::duration<double>(now - rate_wall_).count();
    if (span >= kRateWindow) {
      steps_per_second_ = (run_->step_count() - rate_steps_) / span;
      sim_per_second_ = (run_->time() - rate_sim_) / span;
      rate_wall_ = now;
      rate_steps_ = run_->step_count();
      rate_sim_ = run_->time();
    }
    // A snapshot with its status costs passes over every bond (elastic energy, strain): on a
    // large body as much as a step or more. While stepping, publish at most so often that it
    // takes a tenth of the thread's time (120 times a second when it is cheap).
    const double since_publish = std::chrono::duration<double>(now - last_publish).count();
    if (publish_now || since_publish >= std::max(kPublishInterval, 9.0 * publish_seconds)) {
      publish();
      last_publish = Clock::now();
      publish_seconds = std::chrono::duration<double>(last_publish - now).count();
    }
  }
}

}  // namespace periflex
