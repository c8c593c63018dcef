// A checkpoint folder as a run to replay: the checkpoints of one scene, sorted by time, each
// loaded on demand, and the run record (output/run_record.h) that says which scene they belong
// to. `periflex run --render DIR` and `periflex play DIR` draw from it.
#pragma once

#include <string>
#include <vector>

#include "output/checkpoint_file.h"
#include "output/run_record.h"
#include "solve/sim_state.h"

namespace periflex {

struct CheckpointEntry {
  std::string path;
  CheckpointHeader header;  // time, steps, scene hash
};

class CheckpointFolder {
 public:
  // Lists the *.pfstate files of `dir` by their headers. Throws CheckpointError naming the file
  // for a folder that is missing, holds no checkpoint, has no run record, or holds a file that
  // is not a readable checkpoint or belongs to another scene than the record (a mixed folder).
  // Two files at the same time (a run restarted into its own folder) count once.
  explicit CheckpointFolder(const std::string& dir);

  const std::string& dir() const { return dir_; }
  const RunRecord& record() const { return record_; }
  size_t size() const { return entries_.size(); }
  const CheckpointEntry& entry(size_t index) const { return entries_.at(index); }

  // The state of checkpoint `index`. Throws CheckpointError naming the file when it cannot be
  // read (truncated, damaged, removed since listed).
  SimState load(size_t index) const;

 private:
  std::string dir_;
  RunRecord record_;
  std::vector<CheckpointEntry> entries_;
};

}  // namespace periflex
