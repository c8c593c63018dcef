#include "io/state_replay.h"

#include <cmath>
#include <filesystem>

#include "io/checkpoint_replay.h"
#include "io/vtk_replay.h"

namespace periflex {

size_t StateReplay::nearest(double t) const {
  size_t best = 0;
  for (size_t k = 1; k < times_.size(); ++k)
    if (std::abs(times_[k] - t) < std::abs(times_[best] - t)) best = k;
  return best;
}

std::unique_ptr<StateReplay> open_state_replay(const std::string& dir) {
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::path(dir) / kVtkCollectionName, ec))
    return std::make_unique<VtkReplay>(dir);
  return std::make_unique<CheckpointReplay>(dir);
}

}  // namespace periflex
