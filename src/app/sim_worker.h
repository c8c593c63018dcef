// The simulation thread (as MuJoCo's simulate runs physics): it owns the model, steps it at
// the requested pace, applies requests from the CommandQueue between steps, and publishes
// snapshots through a SnapshotExchange so the render thread never waits for a step.
// A NumericalError pauses the run and is reported in the status; a scene that fails to load
// on reload or switch is reported and the old model kept. No GL here.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/command_queue.h"
#include "app/event_log.h"
#include "app/sim_command.h"
#include "app/snapshot_exchange.h"
#include "app/state_history.h"
#include "solve/simulation.h"

namespace periflex {

// What the worker steps: the Simulation in the program, small fakes in the tests.
class SteppedRun {
 public:
  virtual ~SteppedRun() = default;
  virtual void step() = 0;                                     // may throw NumericalError
  virtual double time() const = 0;
  virtual long step_count() const = 0;
  virtual double end_time() const = 0;
  virtual const ModelInfo& info() const = 0;
  virtual void fill_snapshot(Snapshot& out) const = 0;
  virtual LiveSettings settings() const = 0;
  virtual void apply(const LiveSettings& settings) = 0;         // may throw InputError
  // returns the spring's total stiffness [N/m] (0: nothing held)
  virtual double set_mouse_spring(const std::optional<MouseSpring>& spring) = 0;
  // whether fill_snapshot adds the joints' reactions (a solve of the equations of motion more
  // per snapshot, asked only while the window shows them)
  virtual void set_reactions(bool /*wanted*/) {}
  // cuts the bonds the segment crosses (Simulation::cut_bonds); returns the pairs cut. A model
  // without flexible bodies has nothing to cut.
  virtual long cut_bonds(const Vec2& /*from*/, const Vec2& /*to*/, const std::vector<float>& /*drawn_x*/,
                         const std::vector<float>& /*drawn_y*/) {
    return 0;
  }
  // Puts back the state the model started in (nothing held by the mouse), keeping the live
  // settings; false when the model cannot, and the worker then builds it again.
  virtual bool reset_to_start() { return false; }
  // Copies out the whole state, or puts one back (the window's history, app/state_history.h);
  // false when the model cannot, and the window then keeps no history.
  virtual bool save_state(SimState& /*out*/) const { return false; }
  virtual bool restore_state(const SimState& /*in*/) { return false; }
};

// How the worker gets scenes and models: load reads a file (throws InputError), build makes a
// ready-to-step model from a scene (throws InputError or NumericalError).
// started (optional) runs first thing on the simulation thread, for per-thread set-up.
struct RunFactory {
  std::function<SceneDef(const std::string& path, const std::vector<std::string>& overrides)> load;
  std::function<std::unique_ptr<SteppedRun>(const SceneDef& scene)> build;
  std::function<void()> started;
};

// The factory the program uses: scene/scene_loader.h and solve/simulation.h. The simulation
// thread's parallel force loops use one core fewer than the machine has (at least one), so
// drawing keeps a core: with every core busy stepping, the solver's threads and the render
// thread take turns and both slow down many times. A set OMP_NUM_THREADS is followed instead.
RunFactory live_run_factory();

// A copy of the worker's state for the panels, refreshed whenever a snapshot is published.
struct WorkerStatus {
  bool running = false;
  double time = 0.0;
  long step = 0;
  double end_time = 0.0;
  double speed = 1.0;                 // real-time factor; <= 0: as fast as possible
  double steps_per_second = 0.0;      // measured over the last half second of running
  double sim_seconds_per_second = 0.0;
  LiveSettings settings;
  ModelInfo info;
  std::string scene_path;
  std::string scene_name;
  std::string scene_description;      // its scene.description key
  std::vector<std::string> geometry_files;  // files the flexible bodies' shapes were read from
  // per flexible body: where its geometry came from and the box its particles fill
  std::vector<std::string> geometry_summary;
  long generation = 0;                // grows when the model is rebuilt (reset, reload, switch)
  long scene_generation = 0;          // grows when a scene is (re)loaded from disk
  std::optional<NumericalDiagnostic> numerical_error;  // the last failure; cleared by reset/reload
  std::string numerical_message;      // its what()
  std::string load_error;             // the last failed reload or switch; cleared by a good one
  long commands_applied = 0;
  bool recording = false;
  double mouse_stiffness = 0.0;       // of the mouse spring held now [N/m]; 0: none
  // the last refused live setting (its key as set_live_parameter names it, "" when it is not
  // one field's) and why; cleared by an accepted change or a rebuilt model
  std::string rejected_key, rejected_message;
  // the history ring (app/state_history.h): its cadence [s] (0: off), budget and use [bytes],
  // states kept and the times of the oldest and newest
  double history_interval = 0.0;
  size_t history_budget = 0, history_bytes = 0, history_states = 0;
  double history_first = 0.0, history_last = 0.0;
  bool history_compressed = false;   // the states are kept compressed (large ones)
  bool history_too_large = false;    // the last state was larger than the whole budget
  long scrub = -1;                   // the history state shown (paused); -1: the live state
};

class SimWorker {
 public:
  // Loads and builds the first scene in the calling thread, so a bad scene is reported
  // before any window opens. Throws InputError or NumericalError. Call start() to step.
  SimWorker(RunFactory factory, const std::string& scene_path, std::vector<std::string> overrides,
            EventLog& log);
  ~SimWorker();
  SimWorker(const SimWorker&) = delete;
  SimWorker& operator=(const SimWorker&) = delete;

  // Starts the simulation thread, paused unless `run` is true, at real-time factor `speed`.
  void start(bool run, double speed);
  // Asks the thread to finish after the current step and waits for it.
  void stop();

  // Queues a request; it is applied between two steps.
  void send(SimCommand command) { commands_.push(std::move(command)); }
  // Render side: take the newest snapshot (true when it changed) and read it.
  bool update_snapshot() { return exchange_.update(); }
  const Snapshot& snapshot() const { return exchange_.front(); }
  bool has_snapshot() const { return exchange_.has_front(); }
  WorkerStatus status() const;

  // Render side: the next snapshot published for recording (at a fixed simulated interval),
  // if any. The simulation thread waits when `kMaxRecorded` are pending, which bounds memory.
  bool take_recorded(Snapshot& out);
  static constexpr size_t kMaxRecorded = 8;

 private:
  void loop();
  // the requests (sim_worker_commands.cpp): apply one, through the handler of its type
  void apply(SimCommand& command);
  template <typename Action>
  void handle(Action& action, const std::string& by);
  // parts the handlers share: refusing to step after a failure, starting to run, settings taken
  bool refused_after_failure(const char* verb, const std::string& by);
  void start_running(const std::string& by);
  void settings_accepted();
  void rebuild(const SceneDef& scene, bool keep_settings, const char* what);
  // What follows a new or reset model: paused at its start, errors cleared, the log told.
  void restarted(const std::string& scene_name, const char* what);
  void load_from_disk(const std::string& path, const std::vector<std::string>& overrides, const char* what);
  void publish();
  void record_if_due();
  void reanchor();
  // the history (sim_worker_history.cpp)
  void save_history_if_due();
  void history_defaults();
  bool keep_live(const std::string& by);
  void scrub_to(size_t index, const std::string& by);
  void scrub_step(int direction, const std::string& by);
  void leave_scrub(const char* why);

  using Clock = std::chrono::steady_clock;

  RunFactory factory_;
  EventLog& log_;
  CommandQueue<SimCommand> commands_;
  SnapshotExchange<Snapshot> exchange_;
  std::thread thread_;

  // owned by the simulation thread (and by the constructor before start)
  std::unique_ptr<SteppedRun> run_;
  SceneDef scene_;
  std::string scene_path_;
  std::vector<std::string> overrides_;
  bool running_ = false;
  int pending_steps_ = 0;
  double speed_ = 1.0;
  Clock::time_point anchor_wall_;
  double anchor_sim_ = 0.0;
  Clock::time_point rate_wall_;
  long rate_steps_ = 0;
  double rate_sim_ = 0.0;
  double steps_per_second_ = 0.0, sim_per_second_ = 0.0;
  double record_interval_ = 0.0, record_start_ = 0.0;
  long record_marks_ = 0;          // marks already recorded
  double mouse_stiffness_ = 0.0;   // of the spring held by the model (0: none)
  std::string rejected_key_, rejected_message_;
  void note_rejection(const std::exception& e);
  long generation_ = 0, scene_generation_ = 0, applied_ = 0;
  std::optional<NumericalDiagnostic> numerical_error_;
  std::string numerical_message_, load_error_;

  mutable std::mutex status_mutex_;
  WorkerStatus status_;

  std::mutex record_mutex_;
  std::condition_variable record_space_;
  std::deque<Snapshot> recorded_;
  std::atomic<bool> quitting_{false};

  // the history ring, its settings, and the state shown while scrubbing (-1: the live one)
  StateHistory history_;
  bool history_auto_ = true;       // the cadence follows each scene until the user sets one
  long scrub_ = -1;
};

// The window's default history budget [bytes].
constexpr size_t kDefaultHistoryBudget = size_t{256} << 20;
// The default cadence: this many states over the scene's end time.
constexpr double kDefaultHistoryStates = 500.0;

}  // namespace periflex
