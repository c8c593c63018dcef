// Replaying a checkpoint folder: the scene's model built once from the folder's run record, and
// any of its states put in place and drawn through the same Snapshot a live run draws. The first
// state is the scene's start (t = 0) when no checkpoint is at t = 0, so a replay begins where the
// run began. No step is taken.
//
//   CheckpointReplay replay("out/plate/checkpoints");
//   for (size_t k = 0; k < replay.size(); ++k) { replay.show(k, snapshot); draw(snapshot); }
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "output/checkpoint_folder.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {

class CheckpointReplay {
 public:
  // Lists the folder and builds the model of its scene. Throws CheckpointError naming the file
  // (see CheckpointFolder; and a scene file that has changed since the run, or is gone), and
  // InputError / NumericalError as building and initialising the scene does.
  explicit CheckpointReplay(const std::string& dir);

  // States to show, in time order (the start first when no checkpoint is at t = 0).
  size_t size() const { return times_.size(); }
  double time(size_t index) const { return times_.at(index); }
  const std::vector<double>& times() const { return times_; }
  // The file of state `index`; empty for the start.
  std::string path(size_t index) const;
  const CheckpointFolder& folder() const { return folder_; }
  const SceneDef& scene() const { return scene_; }
  // The end time of the run that wrote the folder (its --until, else the scene's).
  double end_time() const { return folder_.record().until.value_or(scene_.solver.end_time); }
  // The model, holding the state shown last (for its info, settings and sample).
  const Simulation& simulation() const { return *sim_; }

  // Puts state `index` in place and fills `out` from it. Throws CheckpointError naming the file
  // when the checkpoint cannot be read or does not fit the model.
  void show(size_t index, Snapshot& out);
  // The state shown last (index), or none yet (size()).
  size_t shown() const { return shown_; }
  // The index of the state nearest to time t.
  size_t nearest(double t) const;

 private:
  CheckpointFolder folder_;
  SceneDef scene_;
  std::unique_ptr<Simulation> sim_;
  SimState start_;
  bool start_listed_ = false;   // index 0 is the scene's start
  std::vector<double> times_;
  size_t shown_ = 0;
};

}  // namespace periflex
