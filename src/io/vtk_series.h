// Snapshots for ParaView: one .vtu file of particles and one .vtp file of rigid-body shapes per
// snapshot in a directory, and a .pvd collection (snapshots.pvd) listing them with their times as parts 0
// (particles) and 1 (bodies), rewritten atomically after each snapshot, so a killed run leaves a
// collection that opens.
#pragma once

#include <string>
#include <vector>

#include "solve/snapshot.h"

namespace periflex {

class VtkSeries {
 public:
  explicit VtkSeries(std::string directory);
  void write(const Snapshot& snapshot);
  void finish() {}
  long count() const { return snapshots_; }

 private:
  std::string directory_;
  struct Entry { double time; int part; std::string file; };
  std::vector<Entry> entries_;
  long snapshots_ = 0;
};

}  // namespace periflex
