// The Simulation a Python script drives (the module periflex, python/): a scene loaded as the
// program loads it, stepped with the interpreter free to run other threads, interrupted by
// Ctrl-C between steps, its state saved and restored as bytes, its live settings changed as the
// window changes them. Arrays and dictionaries are made in py_arrays.cpp and module.cpp.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene_def.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {

// Where a scene comes from: a file, or TOML text with the name its messages show.
struct SceneSource {
  std::string path;          // a file to read, or "" for text
  std::string text;          // TOML text (path empty)
  std::string display_name;  // the name messages give the text ("<string>")
};

class PySimulation {
 public:
  // Loads the scene with the program's checks (the integrator exists, the scene's budget, the
  // warnings about geometry that does nothing). Throws InputError as `periflex run` would.
  PySimulation(const SceneSource& source, const std::vector<std::string>& overrides);

  Simulation& sim() { return *sim_; }
  const Simulation& sim() const { return *sim_; }
  // The simulation, shared with the arrays that view its state (a rebuild by set() replaces it;
  // the views taken before keep the one they show alive).
  const std::shared_ptr<Simulation>& shared_sim() const { return sim_; }
  const SceneSource& source() const { return source_; }
  const std::vector<std::string>& overrides() const { return overrides_; }
  // the warnings the program prints to stderr when it loads the scene
  const std::vector<std::string>& scene_warnings() const { return scene_warnings_; }

  // n steps of dt (the GIL released; Ctrl-C checked at least every kSignalCheckSeconds).
  void step(long n);
  // Steps up to exactly t (the last one shortened), as Simulation::advance_to.
  void advance_to(double t);

  // Changes one live setting as the window's script does (keys of app/sim_command.h, also
  // spelled as in the scene: "solver.dt", "solver.correction.alpha", ...), or a flexible body's
  // fracture constant (flex_body.NAME.material.fracture_energy or .critical_stretch: the model
  // is built again with it and continues from the state now, see rebuild_with). Throws
  // InputError naming the key for an unknown key or a refused value; nothing changes then.
  void set(const std::string& key, const std::string& value);

  // The state as bytes (output/state_codec.h) and back.
  std::vector<uint8_t> save_state() const;
  void restore_state(const uint8_t* bytes, size_t size);

  // A checkpoint file as `periflex run --checkpoint-every` writes it, and back: the file names
  // the scene by a hash of its text and overrides, so it is restored only into the same scene.
  // A scene read from a file is also recorded beside it (run.json, as a checkpointing run
  // records it), unless that folder records another scene; recorded_scene() reads it back.
  void write_checkpoint(const std::string& path);
  void restore_checkpoint(const std::string& path);

  // A snapshot filled now (positions in floats, damage, bond counts), reused between calls.
  const Snapshot& snapshot();
  // The snapshot a picture is drawn from, as `periflex run` fills it: before the first step, of
  // the initial conditions made consistent (initialize()), as the run's first frame shows them.
  Snapshot picture_snapshot();
  // Makes the initial conditions consistent (Simulation::initialize) unless the simulation has
  // stepped, been initialised or had a state put back: the state is then left as it is.
  void initialize_once();

 private:
  // Steps `n` times `one_step` with the GIL released (kept for a call shorter than
  // kHoldGilSeconds), returning to check signals.
  template <class OneStep>
  void step_interruptibly(long n, OneStep one_step);
  uint64_t scene_hash() const;
  void record_scene_beside(const std::string& checkpoint_path, uint64_t hash) const;
  // The scene loaded again with one more override, its model built, and the state and live
  // settings of now put in it: for the constants that decide only when bonds break, which the
  // state does not depend on (the bonds broken so far are state and stay broken).
  void rebuild_with(const std::string& override_text);
  // Throws RuntimeError while another thread steps this simulation (stepping runs without the
  // GIL, so two threads could otherwise step, or restore and step, at once).
  void refuse_when_busy(const char* what) const;

  std::atomic<bool> busy_{false};
  bool initialized_ = false;  // Simulation::initialize called, or made unnecessary
  double typical_step_seconds_ = 0.0;  // of the last stretch stepped without the GIL (0: none yet)

  SceneSource source_;
  std::vector<std::string> overrides_;
  std::vector<std::string> scene_warnings_;
  std::shared_ptr<Simulation> sim_;
  Snapshot snapshot_;
  long snapshot_step_ = -1;       // the step snapshot_ was filled at (-1: never)
  double snapshot_time_ = -1.0;
};

// The scene file and overrides a checkpoint belongs to, from the run.json beside it (written by
// `periflex run --checkpoint-every` and by write_checkpoint). InputError naming the file when
// its folder records none.
std::pair<std::string, std::vector<std::string>> recorded_scene(const std::string& checkpoint_path);

// Seconds of stepping between two looks for Ctrl-C.
constexpr double kSignalCheckSeconds = 0.05;
// A call expected to step for less than this keeps the GIL (at most kMaxHeldSteps steps).
constexpr double kHoldGilSeconds = 50e-6;
constexpr long kMaxHeldSteps = 64;

}  // namespace periflex
