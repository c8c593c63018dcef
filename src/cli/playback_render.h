// `periflex run DIR --render ...` with DIR a checkpoint folder or a run's VTK series
// (io/state_replay.h): the states drawn in time order (a checkpoint folder's scene start
// first), one frame each, through the same Snapshot and recorder as a live run's frames. Nothing
// is simulated.
#pragma once

#include "cli/run_command.h"

namespace periflex {

// Returns the exit code: 0 ok; 2 a folder that cannot be replayed (naming the file) or a flag
// that does not apply to one (naming the flag); 1 a recording that failed.
int render_checkpoint_folder(RunOptions options);

}  // namespace periflex
