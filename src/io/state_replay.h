// States of a finished run shown again without simulating: a checkpoint folder
// (io/checkpoint_replay.h: every state whole) or the VTK series the run wrote
// (io/vtk_replay.h: positions, velocities, damage and strain). Both build the model of the
// run's scene once and fill the same Snapshot a live run draws, so playback in the window and
// `run DIR --render` draw through one path.
//
//   std::unique_ptr<StateReplay> replay = open_state_replay("out/plate/checkpoints");
//   for (size_t k = 0; k < replay->size(); ++k) { replay->show(k, snapshot); draw(snapshot); }
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene_def.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {

class StateReplay {
 public:
  virtual ~StateReplay() = default;

  // States to show, in time order.
  size_t size() const { return times_.size(); }
  double time(size_t index) const { return times_.at(index); }
  const std::vector<double>& times() const { return times_; }
  // The index of the state nearest to time t.
  size_t nearest(double t) const;

  // The file state `index` comes from; empty for the scene's start.
  virtual std::string path(size_t index) const = 0;
  virtual const SceneDef& scene() const = 0;
  // The scene file the run loaded.
  virtual const std::string& scene_path() const = 0;
  // The end time of the run that wrote the states.
  virtual double end_time() const = 0;
  // The model of the run's scene (for its info and settings).
  virtual const Simulation& simulation() const = 0;
  // Whether show() fills the snapshot's series row (output/series_row.h); a VTK series holds none.
  virtual bool has_series_rows() const = 0;
  // Fills `out` with state `index`. Throws CheckpointError (output/checkpoint_file.h) naming the
  // file when it cannot be read or does not fit the model.
  virtual void show(size_t index, Snapshot& out) = 0;

 protected:
  std::vector<double> times_;
};

// The replay of `dir`: a VTK series when it holds snapshots.pvd, else a checkpoint folder.
// Throws CheckpointError naming what cannot be replayed, and InputError / NumericalError as
// building and initialising the scene does.
std::unique_ptr<StateReplay> open_state_replay(const std::string& dir);

}  // namespace periflex
