// Particle snapshots for ParaView: one .vtu file per snapshot in a directory, and a .pvd
// collection listing them with their times (rewritten atomically after each snapshot, so a
// killed run leaves a collection that opens).
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
  long count() const { return static_cast<long>(entries_.size()); }

 private:
  std::string directory_;
  struct Entry { double time; std::string file; };
  std::vector<Entry> entries_;
};

}  // namespace periflex
