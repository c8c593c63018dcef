// Checkpoint files: one Simulation state on disk, to continue a run from (`periflex run SCENE
// --restart FILE`). Layout (docs/state.md): a header (magic, format version, program version,
// hash of the scene as loaded, time, step count, sizes), the state's bytes (output/state_codec.h)
// compressed with libdeflate, and a CRC-32 over header and compressed bytes, so a truncated or
// damaged file is refused rather than restored. Written to a temporary file and renamed, so an
// interrupted run never leaves a partial checkpoint under the final name.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "solve/sim_state.h"

namespace periflex {

// Format version of the files this program writes and reads (5: flexible bodies carry their
// bonds' softening histories).
constexpr uint32_t kCheckpointFormat = 5;

struct CheckpointHeader {
  uint32_t format = kCheckpointFormat;
  std::string program_version;   // PERIFLEX_VERSION of the writer
  uint64_t scene_hash = 0;       // scene_hash() of the scene the state belongs to
  double time = 0.0;
  int64_t steps = 0;
  double checkpoint_every = 0.0; // the interval of the run that wrote it (its landing instants)
};

// Why a file is no checkpoint this program can read (the message says it).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `state` under `header` to `path` (atomically). Returns the bytes written. Throws
// std::runtime_error naming the path when it cannot be written.
size_t write_checkpoint(const std::string& path, const CheckpointHeader& header, const SimState& state);

// Reads the header only (no decompression): what `path` holds and for which scene.
// Throws CheckpointError for a file that is not a checkpoint or of another format version.
CheckpointHeader read_checkpoint_header(const std::string& path);

// Reads the whole file. Throws CheckpointError saying why for a file that is missing, not a
// checkpoint, of another format version, truncated or damaged (checksum), or undecodable.
SimState read_checkpoint(const std::string& path, CheckpointHeader& header);

// 64-bit FNV-1a of text, for scene hashes.
uint64_t text_hash(const std::string& text, uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace periflex
