// Replaying the VTK series a run wrote (`run --vtk-every N`, io/vtk_series.h): the model of
// the run's scene (named by the summary.json beside the series' folder) built once, and each
// snapshot of the series put in place as a state: the rigid bodies' poses from the .vtp files,
// the particles' positions and velocities from the .vtu files, then the snapshot filled from
// that state with the damage and strain the files hold. What the files do not hold is not
// shown: the rigid bodies' velocities are zero, the bonds count as intact for anything but the
// damage and strain, and there is no series row (energies are those of the state so built).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/state_replay.h"

namespace periflex {

// The collection a VTK series folder holds.
inline constexpr const char* kVtkCollectionName = "snapshots.pvd";

class VtkReplay final : public StateReplay {
 public:
  // Reads the collection and builds the scene's model. Throws CheckpointError naming the file
  // (no summary.json beside the folder, a scene whose particles or bodies do not match the
  // files, a file periflex did not write), and InputError / NumericalError as building and
  // initialising the scene does.
  explicit VtkReplay(const std::string& dir);

  std::string path(size_t index) const override;
  const SceneDef& scene() const override { return scene_; }
  const std::string& scene_path() const override { return scene_path_; }
  double end_time() const override { return end_time_; }
  const Simulation& simulation() const override { return *sim_; }
  bool has_series_rows() const override { return false; }
  void show(size_t index, Snapshot& out) override;

 private:
  // the files of one snapshot (either may be absent: a scene writes what it has)
  struct Files {
    std::string particles, bodies;
  };
  std::string dir_, scene_path_;
  SceneDef scene_;
  double end_time_ = 0.0;
  std::unique_ptr<Simulation> sim_;
  SimState start_;
  std::vector<Files> files_;
  long rigid_bodies_ = 0, particles_ = 0;
};

}  // namespace periflex
