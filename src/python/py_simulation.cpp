#include "python/py_simulation.h"

#include <pybind11/pybind11.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "app/sim_command.h"
#include "core/error.h"
#include "output/checkpoint_file.h"
#include "output/run_record.h"
#include "output/state_codec.h"
#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "scene/scene_warnings.h"

namespace py = pybind11;

namespace periflex {

namespace {

// The checks `periflex run` makes after parsing (cli/scene_setup.cpp): the integrator is one
// this program has, the scene fits its budget; then the warnings it prints.
void check_loaded_scene(const SceneDef& scene, std::vector<std::string>& warnings) {
  const auto names = integrator_names();
  if (std::find(names.begin(), names.end(), scene.solver.integrator) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(scene.locate("solver.integrator"), "integrator '" + scene.solver.integrator +
                                                            "' is not available in this program; expected one of: " + list);
  }
  check_scene_budget(scene);
  warnings = scene_warnings(scene);
}

// The window's name of a live setting spelled as a scene key ("solver.dt" -> "dt").
std::string live_key(const std::string& key) {
  if (key == "solver.correction.method") return "correction";
  for (const char* prefix : {"solver.correction.", "solver.", "flex_body."}) {
    const std::string p = prefix;
    if (key.rfind(p, 0) == 0) return key.substr(p.size());
  }
  return key;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, ""}, "cannot read the scene file");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The scene of `source` with `overrides`, checked as `periflex run` checks it.
SceneDef load_checked(const SceneSource& source, const std::vector<std::string>& overrides,
                      std::vector<std::string>& warnings) {
  const SceneDef scene = source.path.empty() ? parse_scene(source.text, source.display_name, overrides)
                                             : load_scene(source.path, overrides);
  check_loaded_scene(scene, warnings);
  return scene;
}

// "flex_body.NAME.material.KEY" for the constants of breaking a rebuild may change live.
bool is_fracture_constant(const std::string& key) {
  const std::string head = "flex_body.";
  if (key.rfind(head, 0) != 0) return false;
  for (const char* tail : {".material.fracture_energy", ".material.critical_stretch"}) {
    const std::string t = tail;
    if (key.size() > head.size() + t.size() && key.compare(key.size() - t.size(), t.size(), t) == 0) return true;
  }
  return false;
}

}  // namespace

PySimulation::PySimulation(const SceneSource& source, const std::vector<std::string>& overrides)
    : source_(source), overrides_(overrides) {
  sim_ = std::make_shared<Simulation>(load_checked(source, overrides, scene_warnings_));
}

void PySimulation::rebuild_with(const std::string& override_text) {
  std::vector<std::string> overrides = overrides_;
  overrides.push_back(override_text);
  std::vector<std::string> warnings;
  auto next = std::make_shared<Simulation>(load_checked(source_, overrides, warnings));
  // the state of now, whole (the integrator's cache too: the forces do not depend on the
  // constants of breaking), under the live settings of now
  initialize_once();
  SimState state;
  sim_->save_state(state);
  next->apply(sim_->settings());
  next->restore_state(state);
  sim_ = std::move(next);
  overrides_ = std::move(overrides);
  scene_warnings_ = std::move(warnings);
  snapshot_step_ = -1;
}

void PySimulation::refuse_when_busy(const char* what) const {
  if (busy_.load()) throw std::runtime_error(std::string(what) + ": the simulation is stepping in another thread");
}

template <class OneStep>
void PySimulation::step_interruptibly(long n, OneStep one_step) {
  if (busy_.exchange(true)) throw std::runtime_error("step: the simulation is stepping in another thread");
  struct Idle {
    std::atomic<bool>& busy;
    ~Idle() { busy = false; }
  } idle{busy_};
  // stepping initialises first (Simulation::step)
  initialized_ = true;
  using Clock = std::chrono::steady_clock;
  // a call whose steps take less than kHoldGilSeconds keeps the interpreter: giving the GIL up
  // and taking it back costs more than such a step (the pendulum's take 2 us), and no other
  // thread waits longer than the interpreter's own switch interval (5 ms) makes it wait anyway
  if (n <= kMaxHeldSteps && typical_step_seconds_ > 0.0 && typical_step_seconds_ * n < kHoldGilSeconds) {
    bool finished = false;
    for (long done = 0; done < n && !finished; ++done) finished = one_step();
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    return;
  }
  const auto check_every = std::chrono::duration<double>(kSignalCheckSeconds);
  long done = 0;
  bool finished = false;
  while (done < n && !finished) {
    // a stretch of steps without the interpreter, then a look for Ctrl-C with it: an
    // interrupt stops between two steps, so the simulation stays usable
    {
      py::gil_scoped_release release;
      const auto start = Clock::now();
      const long before = done;
      do {
        finished = one_step();
        ++done;
      } while (done < n && !finished && Clock::now() - start < check_every);
      typical_step_seconds_ = std::chrono::duration<double>(Clock::now() - start).count() / double(done - before);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

void PySimulation::step(long n) {
  if (n < 0) throw py::value_error("step: n must not be negative, found " + std::to_string(n));
  step_interruptibly(n, [this] {
    sim_->step();
    return false;
  });
}

void PySimulation::advance_to(double t) {
  if (!std::isfinite(t)) throw py::value_error("advance_to: t must be finite");
  // a time already passed (beyond the clock's rounding) is refused, not silently ignored
  if (t < sim_->time() && sim_->time() - t > 1e-12 * std::max(1.0, std::abs(t)))
    throw py::value_error("advance_to: t = " + std::to_string(t) + " s is before the time now, " +
                          std::to_string(sim_->time()) + " s");
  if (sim_->reached(t)) return;
  // step_toward takes no step once the time is t: the count is an upper bound only
  step_interruptibly(std::numeric_limits<long>::max(), [this, t] { return sim_->step_toward(t); });
}

void PySimulation::set(const std::string& key, const std::string& value) {
  refuse_when_busy("set");
  if (is_fracture_constant(key)) {
    rebuild_with(key + "=" + value);
    return;
  }
  LiveSettings settings = sim_->settings();
  const std::string name = live_key(key);
  const std::string problem = set_live_parameter(settings, name, value);
  if (!problem.empty()) throw InputError({"", 0, 0, key}, problem);
  sim_->apply(settings);
}

std::vector<uint8_t> PySimulation::save_state() const {
  refuse_when_busy("save_state");
  SimState state;
  sim_->save_state(state);
  return encode_state(state);
}

void PySimulation::restore_state(const uint8_t* bytes, size_t size) {
  refuse_when_busy("restore_state");
  SimState state;
  try {
    state = decode_state(bytes, size);
  } catch (const std::runtime_error& e) {
    throw py::value_error(std::string("restore_state: not a saved state: ") + e.what());
  }
  try {
    sim_->restore_state(state);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("restore_state: ") + e.what());
  }
  initialized_ = true;
  snapshot_step_ = -1;
}

uint64_t PySimulation::scene_hash() const {
  const std::string text = source_.path.empty() ? source_.text : read_text(source_.path);
  return scene_identity_hash(text, overrides_, std::nullopt, std::nullopt);
}

void PySimulation::write_checkpoint(const std::string& path) {
  refuse_when_busy("write_checkpoint");
  CheckpointHeader header;
  header.program_version = PERIFLEX_VERSION;
  header.scene_hash = scene_hash();
  header.time = sim_->time();
  header.steps = sim_->step_count();
  SimState state;
  sim_->save_state_for_file(state);
  periflex::write_checkpoint(path, header, state);
  record_scene_beside(path, header.scene_hash);
}

void PySimulation::record_scene_beside(const std::string& checkpoint_path, uint64_t hash) const {
  if (source_.path.empty()) return;
  const std::string dir = std::filesystem::absolute(checkpoint_path).parent_path().string();
  try {
    if (read_run_record(dir).scene_hash != hash) return;  // the folder's other scene keeps its record
  } catch (const CheckpointError&) {
    // no record yet (or none this program can read): this one is written
  }
  RunRecord record;
  record.scene_path = std::filesystem::absolute(source_.path).lexically_normal().string();
  record.overrides = overrides_;
  record.scene_hash = hash;
  record.program_version = PERIFLEX_VERSION;
  write_run_record(dir, record);
}

std::pair<std::string, std::vector<std::string>> recorded_scene(const std::string& checkpoint_path) {
  const std::string dir = std::filesystem::absolute(checkpoint_path).parent_path().string();
  RunRecord record;
  try {
    record = read_run_record(dir);
  } catch (const CheckpointError& e) {
    throw InputError({checkpoint_path, 0, 0, ""},
                     std::string("the checkpoint's folder records no scene (") + e.what() +
                         "); give the scene: Simulation.from_checkpoint(path, scene, overrides)");
  }
  return {record.scene_path, record.scene_overrides()};
}

void PySimulation::restore_checkpoint(const std::string& path) {
  const auto refuse = [&](const std::string& why) {
    return InputError({path, 0, 0, ""}, "cannot continue from this checkpoint: " + why);
  };
  refuse_when_busy("restore_checkpoint");
  CheckpointHeader header;
  SimState state;
  try {
    state = read_checkpoint(path, header);
  } catch (const CheckpointError& e) {
    throw refuse(e.what());
  }
  if (header.program_version != PERIFLEX_VERSION)
    throw refuse("written by periflex " + header.program_version + ", this is periflex " + PERIFLEX_VERSION);
  if (header.scene_hash != scene_hash())
    throw refuse("written for another scene, or for this one with other overrides");
  sim_->restore_state(state);
  initialized_ = true;
  snapshot_step_ = -1;
}

const Snapshot& PySimulation::snapshot() {
  refuse_when_busy("reading the particles' fields");
  if (snapshot_step_ != sim_->step_count() || snapshot_time_ != sim_->time()) {
    sim_->fill_snapshot(snapshot_);
    snapshot_step_ = sim_->step_count();
    snapshot_time_ = sim_->time();
  }
  return snapshot_;
}

Snapshot PySimulation::picture_snapshot() {
  refuse_when_busy("render");
  initialize_once();
  return snapshot();
}

void PySimulation::initialize_once() {
  refuse_when_busy("initialize");
  if (initialized_) return;
  sim_->initialize();
  initialized_ = true;
  snapshot_step_ = -1;
}

}  // namespace periflex
