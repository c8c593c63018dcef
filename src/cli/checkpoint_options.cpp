// Scene identity, file names and the checks of `run --restart`.
#include "cli/checkpoint_options.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include "cli/scene_setup.h"
#include "core/error.h"
#include "core/sim_time.h"
#include "output/run_record.h"

namespace periflex {

uint64_t run_scene_hash(const RunOptions& o) {
  std::ifstream in(o.scene_path, std::ios::binary);
  if (!in) throw InputError({o.scene_path, 0, 0, ""}, "cannot read the scene file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return scene_identity_hash(text, o.overrides, o.dt, o.integrator);
}

std::string checkpoint_file_name(long index, double time) {
  char name[96];
  std::snprintf(name, sizeof name, "checkpoint_%06ld_t%.9g.pfstate", index, time);
  return name;
}

std::string interrupted_file_name(double time) {
  char name[96];
  std::snprintf(name, sizeof name, "checkpoint_interrupted_t%.9g.pfstate", time);
  return name;
}

SimState load_restart(const RunOptions& o, uint64_t scene_hash, double end_time, CheckpointHeader& header) {
  const std::string& path = o.restart_path;
  auto refuse = [&](const std::string& why) -> InputError {
    return InputError(flag_location("--restart"), "cannot continue from '" + path + "': " + why);
  };
  SimState state;
  try {
    state = read_checkpoint(path, header);
  } catch (const CheckpointError& e) {
    throw refuse(e.what());
  }
  if (header.program_version != PERIFLEX_VERSION) {
    throw refuse("written by periflex " + header.program_version + ", this is periflex " + PERIFLEX_VERSION +
                 " (a state is continued by the version that wrote it)");
  }
  if (header.scene_hash != scene_hash) {
    throw refuse("written for another scene, or for this one with other --set, --dt or --integrator values "
                 "(give the ones of the run that wrote it)");
  }
  // a state past the end: nothing to run, and no way back
  if (end_time < header.time - time_tolerance(0.0, header.time)) {
    char times[160];
    std::snprintf(times, sizeof times, "its state is at t = %.9g s, after the run's end time %.9g s", header.time,
                  end_time);
    throw InputError(flag_location(o.until ? "--until" : "--restart"),
                     "cannot continue from '" + path + "': " + times + " (give --until beyond it)");
  }
  return state;
}

}  // namespace periflex
