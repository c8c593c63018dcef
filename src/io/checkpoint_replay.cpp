// The model of a checkpoint folder's scene, and its states shown one at a time.
#include "io/checkpoint_replay.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "output/series_row.h"
#include "scene/scene_loader.h"

namespace periflex {

namespace {

// The scene the folder's record names, checked to be the one the states were written for.
SceneDef load_recorded_scene(const RunRecord& record, const std::string& dir) {
  std::ifstream in(record.scene_path, std::ios::binary);
  if (!in) {
    throw CheckpointError("the scene of '" + dir + "', " + record.scene_path +
                          " (named in its run.json), cannot be read");
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (scene_identity_hash(text, record.overrides, record.dt, record.integrator) != record.scene_hash) {
    throw CheckpointError("the scene file " + record.scene_path + " has changed since the checkpoints in '" + dir +
                          "' were written (its hash differs from the one in run.json)");
  }
  return load_scene(record.scene_path, record.scene_overrides());
}

}  // namespace

CheckpointReplay::CheckpointReplay(const std::string& dir)
    : folder_(dir), scene_(load_recorded_scene(folder_.record(), dir)) {
  sim_ = std::make_unique<Simulation>(scene_);
  sim_->initialize();
  sim_->save_state(start_);
  start_listed_ = folder_.entry(0).header.time != 0.0;
  if (start_listed_) times_.push_back(start_.time);
  for (size_t k = 0; k < folder_.size(); ++k) times_.push_back(folder_.entry(k).header.time);
  shown_ = times_.size();
}

std::string CheckpointReplay::path(size_t index) const {
  if (start_listed_ && index == 0) return "";
  return folder_.entry(index - (start_listed_ ? 1 : 0)).path;
}

void CheckpointReplay::show(size_t index, Snapshot& out) {
  if (index >= times_.size()) throw std::out_of_range("no state " + std::to_string(index) + " in the replay");
  if (start_listed_ && index == 0) {
    sim_->restore_state(start_);
  } else {
    const size_t file = index - (start_listed_ ? 1 : 0);
    const SimState state = folder_.load(file);
    try {
      sim_->restore_state(state);
    } catch (const std::invalid_argument& e) {
      throw CheckpointError("'" + folder_.entry(file).path + "' does not fit its scene's model: " + e.what());
    }
  }
  sim_->fill_snapshot(out);
  fill_series_row(*sim_, series_columns_, out);
  shown_ = index;
}

}  // namespace periflex
