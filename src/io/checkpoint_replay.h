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
#include "io/state_replay.h"

namespace periflex {

class CheckpointReplay final : public StateReplay {
 public:
  // Lists the folder and builds the model of its scene. Throws CheckpointError naming the file
  // (see CheckpointFolder; and a scene file that has changed since the run, or is gone), and
  // InputError / NumericalError as building and initialising the scene does.
  explicit CheckpointReplay(const std::string& dir);

  // The states: the start first when no checkpoint is at t = 0, then the checkpoints.
  std::string path(size_t index) const override;
  const CheckpointFolder& folder() const { return folder_; }
  const SceneDef& scene() const override { return scene_; }
  const std::string& scene_path() const override { return folder_.record().scene_path; }
  // The run's --until, else the scene's end time.
  double end_time() const override { return folder_.record().until.value_or(scene_.solver.end_time); }
  // The model, holding the state shown last (for its info, settings and sample).
  const Simulation& simulation() const override { return *sim_; }
  bool has_series_rows() const override { return true; }
  // Puts state `index` in place and fills `out` from it, its series row included.
  void show(size_t index, Snapshot& out) override;
  // The state shown last (index), or none yet (size()).
  size_t shown() const { return shown_; }

 private:
  CheckpointFolder folder_;
  SceneDef scene_;
  std::unique_ptr<Simulation> sim_;
  SimState start_;
  bool start_listed_ = false;   // index 0 is the scene's start
  size_t shown_ = 0;
  std::shared_ptr<const std::vector<std::string>> series_columns_;
};

}  // namespace periflex
