// What a checkpoint folder needs to be replayed on its own: the scene the states belong to, as
// the writing run loaded it (the file, --set overrides, --dt, --integrator). A checkpointing run
// writes it as `run.json` beside its checkpoints; playback builds the model from it and checks
// that the scene file still hashes to the value in every checkpoint's header.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace periflex {

struct RunRecord {
  std::string scene_path;               // absolute path of the scene file
  std::vector<std::string> overrides;   // --set values in order
  std::optional<double> dt;             // --dt
  std::optional<std::string> integrator;  // --integrator
  std::optional<double> until;          // --until (the run's end time; not part of the scene's identity)
  uint64_t scene_hash = 0;              // scene_identity_hash() when written
  std::string program_version;          // the writer's PERIFLEX_VERSION

  // The overrides that load the scene as the run did: --set, then --dt and --integrator as
  // solver.dt / solver.integrator (the number printed with every digit).
  std::vector<std::string> scene_overrides() const;
};

// The file name of the record inside a checkpoint folder.
inline constexpr const char* kRunRecordName = "run.json";

// The identity of a scene as a run loads it: 64-bit FNV-1a over the scene file's bytes, the
// --set overrides in order, --dt and --integrator (not --until, threads or output flags).
uint64_t scene_identity_hash(const std::string& scene_text, const std::vector<std::string>& overrides,
                             std::optional<double> dt, const std::optional<std::string>& integrator);

// Writes `dir`/run.json atomically. Throws std::runtime_error naming the file on failure.
void write_run_record(const std::string& dir, const RunRecord& record);

// Reads `dir`/run.json. Throws CheckpointError (output/checkpoint_file.h) naming the file when it
// is missing or not a record this program wrote.
RunRecord read_run_record(const std::string& dir);

}  // namespace periflex
