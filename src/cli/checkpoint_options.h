// Checkpoints in `periflex run`: which scene a file belongs to, what the files are called, and
// the refusal of a file the run cannot continue from (exit 2, naming the file and the reason).
#pragma once

#include <cstdint>
#include <string>

#include "cli/run_command.h"
#include "output/checkpoint_file.h"
#include "scene/scene_def.h"
#include "solve/sim_state.h"

namespace periflex {

// The identity of the scene as this run loads it: the scene file's bytes, the --set overrides
// in order, --dt and --integrator, and the bytes of every file the flexible bodies' shapes were
// read from (point files, images, drawings). --until is left out, so a restart may run further.
// Throws InputError when the scene file cannot be read.
uint64_t run_scene_hash(const RunOptions& options, const SceneDef& scene);

// "checkpoint_000012_t0.0012.pfstate": the k-th checkpoint, at time t = k T.
std::string checkpoint_file_name(long index, double time);

// "checkpoint_interrupted_t0.00123.pfstate": the state an interrupted run reached.
std::string interrupted_file_name(double time);

// The state in options.restart_path with its header. Throws InputError at --restart naming the
// file and why it cannot be continued from: unreadable, not a checkpoint, another format or
// program version, another scene (or other overrides, or changed shape files), truncated or
// damaged; at --until (or --restart) when the state lies after the scene's end time.
SimState load_restart(const RunOptions& options, const SceneDef& scene, uint64_t scene_hash, CheckpointHeader& header);

}  // namespace periflex
