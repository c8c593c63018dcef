#include "io/vtk_replay.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "output/checkpoint_file.h"
#include "io/vtk_reader.h"
#include "scene/scene_loader.h"

namespace periflex {

namespace fs = std::filesystem;

namespace {

// The scene of the run that wrote the series: the summary.json of its output folder (the
// series' parent) names the file and the --set values.
struct RunScene {
  std::string path;
  std::vector<std::string> overrides;
  double simulated_time = 0.0;
};

RunScene run_scene_of(const std::string& dir) {
  const fs::path summary = fs::path(dir).lexically_normal().parent_path() / "summary.json";
  std::ifstream in(summary);
  if (!in) {
    throw CheckpointError("no summary.json beside the VTK series '" + dir + "' (looked for " + summary.string() +
                          "): the series is replayed in the scene its run's summary names");
  }
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    RunScene r;
    r.path = j.at("scene_path").get<std::string>();
    if (j.contains("set")) r.overrides = j.at("set").get<std::vector<std::string>>();
    if (j.contains("simulated_time") && j.at("simulated_time").is_number())
      r.simulated_time = j.at("simulated_time").get<double>();
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw CheckpointError("'" + summary.string() + "' is not a readable run summary: " + e.what());
  }
}

}  // namespace

VtkReplay::VtkReplay(const std::string& dir) : dir_(dir) {
  // the snapshots: a particles file and a bodies file per time, in the collection's order
  const std::vector<VtkDataSet> sets = read_vtk_collection((fs::path(dir) / kVtkCollectionName).string());
  for (const VtkDataSet& d : sets) {
    const bool same = !files_.empty() && times_.back() == d.time &&
                      (d.part == 1 ? files_.back().bodies.empty() : files_.back().particles.empty());
    if (!same) {
      files_.emplace_back();
      times_.push_back(d.time);
    }
    (d.part == 1 ? files_.back().bodies : files_.back().particles) = (fs::path(dir) / d.file).string();
  }

  const RunScene run = run_scene_of(dir);
  scene_path_ = run.path;
  if (!fs::is_regular_file(scene_path_)) {
    throw CheckpointError("the scene of the VTK series '" + dir + "', " + scene_path_ +
                          ", is gone (moved or deleted since the run)");
  }
  scene_ = load_scene(scene_path_, run.overrides);
  end_time_ = std::max(run.simulated_time, times_.back());
  sim_ = std::make_unique<Simulation>(scene_);
  sim_->initialize();
  sim_->save_state(start_);
  particles_ = static_cast<long>(sim_->info().particles);
  rigid_bodies_ = (static_cast<long>(start_.q.size()) - 2 * particles_) / 3;
}

std::string VtkReplay::path(size_t index) const {
  const Files& f = files_.at(index);
  return f.particles.empty() ? f.bodies : f.particles;
}

void VtkReplay::show(size_t index, Snapshot& out) {
  if (index >= files_.size()) throw std::out_of_range("no state " + std::to_string(index) + " in the replay");
  const Files& f = files_[index];
  SimState state = start_;
  state.time = times_[index];
  state.qd.setZero();
  const auto n = static_cast<size_t>(particles_);
  std::vector<double> damage, strain;
  long step = static_cast<long>(index);
  if (!f.particles.empty()) {
    const VtkArrays a = read_vtk_arrays(f.particles);
    const std::vector<double>& position = a.get("position", 3 * n);
    const std::vector<double>& velocity = a.get("velocity", 3 * n);
    damage = a.get("damage", n);
    strain = a.get("strain", n);
    if (a.arrays.count("STEP")) step = static_cast<long>(a.get("STEP", 1)[0]);
    const long first = 3 * rigid_bodies_;
    for (size_t i = 0; i < n; ++i) {
      state.q[first + 2 * i] = position[3 * i];
      state.q[first + 2 * i + 1] = position[3 * i + 1];
      state.qd[first + 2 * i] = velocity[3 * i];
      state.qd[first + 2 * i + 1] = velocity[3 * i + 1];
    }
  } else if (particles_ > 0) {
    throw CheckpointError("the VTK series '" + dir_ + "' has no particles file at t = " + std::to_string(times_[index]) +
                          " for a scene with particles");
  }
  if (!f.bodies.empty()) {
    // one cell per shape: each carries its body's index (0: the ground) and pose
    const VtkArrays a = read_vtk_arrays(f.bodies);
    const auto cells = a.arrays.count("body") ? a.arrays.at("body").size() : 0;
    const std::vector<double>& body = a.get("body", cells);
    const std::vector<double>& position = a.get("position", 3 * cells);
    const std::vector<double>& angle = a.get("angle", cells);
    for (size_t c = 0; c < cells; ++c) {
      const long k = static_cast<long>(body[c]) - 1;
      if (k < 0) continue;
      if (k >= rigid_bodies_)
        throw CheckpointError("'" + f.bodies + "' names body " + std::to_string(k + 1) + "; the scene " + scene_path_ +
                              " has " + std::to_string(rigid_bodies_));
      state.q[3 * k] = position[3 * c];
      state.q[3 * k + 1] = position[3 * c + 1];
      state.q[3 * k + 2] = angle[c];
    }
    if (f.particles.empty() && a.arrays.count("STEP")) step = static_cast<long>(a.get("STEP", 1)[0]);
  }
  state.steps = step;
  sim_->restore_state(state);
  sim_->fill_snapshot(out);
  // what the files say of the bonds: each particle's damage and largest stretch
  if (!damage.empty()) {
    out.damage.assign(damage.begin(), damage.end());
    out.strain.assign(strain.begin(), strain.end());
    out.max_damage = damage.empty() ? 0.0 : *std::max_element(damage.begin(), damage.end());
  }
  out.series_columns.reset();
  out.series.clear();
}

}  // namespace periflex
