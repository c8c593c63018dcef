// Scene identity, file names and the checks of `run --restart`.
#include "cli/checkpoint_options.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli/scene_setup.h"
#include "core/error.h"
#include "core/sim_time.h"
#include "output/checkpoint_file.h"
#include "output/run_record.h"
#include "scene/file_shape_reader.h"

namespace periflex {

namespace {

// The bytes of a file; empty when it cannot be read (a shape's file was read when the scene loaded).
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The files the scene's flexible bodies were read from, in body order.
std::vector<std::string> shape_files(const SceneDef& scene) {
  std::vector<std::string> files;
  for (const FlexBodyDef& flex : scene.flex_bodies)
    if (!geometry_file(flex).empty()) files.push_back(geometry_file(flex));
  return files;
}

}  // namespace

uint64_t run_scene_hash(const RunOptions& o, const SceneDef& scene) {
  std::ifstream in(o.scene_path, std::ios::binary);
  if (!in) throw InputError({o.scene_path, 0, 0, ""}, "cannot read the scene file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint64_t hash = scene_identity_hash(text, o.overrides, o.dt, o.integrator);
  for (const std::string& file : shape_files(scene)) hash = text_hash(file_bytes(file), hash);
  return hash;
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

SimState load_restart(const RunOptions& o, const SceneDef& scene, uint64_t scene_hash, CheckpointHeader& header) {
  const double end_time = scene.solver.end_time;
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
    std::string files;
    for (const std::string& file : shape_files(scene)) files += (files.empty() ? "" : ", ") + file;
    throw refuse("written for another scene, or for this one with other --set, --dt or --integrator values "
                 "(give the ones of the run that wrote it)" +
                 (files.empty() ? std::string() : ", or the files its shapes were read from changed since (" + files + ")"));
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
