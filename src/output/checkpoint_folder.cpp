// Listing a checkpoint folder: headers only, sorted by time, one scene.
#include "output/checkpoint_folder.h"

#include <algorithm>
#include <filesystem>

namespace periflex {

namespace fs = std::filesystem;

CheckpointFolder::CheckpointFolder(const std::string& dir) : dir_(dir) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) throw CheckpointError("'" + dir + "' is not a folder");
  record_ = read_run_record(dir);
  // the files in name order first, so the one kept of two at the same time does not depend on
  // the directory's order
  std::vector<std::string> files;
  for (const auto& item : fs::directory_iterator(dir, error)) {
    if (item.path().extension() == ".pfstate" && item.is_regular_file()) files.push_back(item.path().string());
  }
  if (error) throw CheckpointError("cannot list '" + dir + "': " + error.message());
  std::sort(files.begin(), files.end());
  for (const std::string& path : files) {
    CheckpointEntry entry{path, {}};
    try {
      entry.header = read_checkpoint_header(path);
    } catch (const CheckpointError& e) {
      throw CheckpointError("'" + path + "': " + e.what());
    }
    if (entry.header.scene_hash != record_.scene_hash) {
      throw CheckpointError("'" + path + "' belongs to another scene than the folder's " + kRunRecordName + " (" +
                            record_.scene_path + "): a folder replays the checkpoints of one run");
    }
    entries_.push_back(std::move(entry));
  }
  if (entries_.empty()) throw CheckpointError("'" + dir + "' holds no checkpoint (*.pfstate)");
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const CheckpointEntry& a, const CheckpointEntry& b) { return a.header.time < b.header.time; });
  entries_.erase(std::unique(entries_.begin(), entries_.end(),
                             [](const CheckpointEntry& a, const CheckpointEntry& b) {
                               return a.header.time == b.header.time;
                             }),
                 entries_.end());
}

SimState CheckpointFolder::load(size_t index) const {
  const CheckpointEntry& e = entries_.at(index);
  CheckpointHeader header;
  try {
    return read_checkpoint(e.path, header);
  } catch (const CheckpointError& error) {
    throw CheckpointError("'" + e.path + "': " + error.what());
  }
}

}  // namespace periflex
