// Runs a study: every method of the grid against the reference, timing the solver alone.
//
//   StudyDef study = load_study("scenes/studies/pendulum.toml");
//   StudyResult result = run_study(study, [](const std::string& line) { std::puts(line.c_str()); });
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include "scene/scene_def.h"
#include "study/study_def.h"
#include "study/study_result.h"

namespace periflex {

using StudyLog = std::function<void(const std::string&)>;
// Asked before every step of every run: true when the study is to stop (Ctrl-C).
using StudyStop = std::function<bool()>;

// Thrown when `stop` ends a run that the study cannot do without (the converged reference).
struct StudyStopped : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Loads the study's scene (with its overrides), runs the reference and every grid point, and
// fills rows and observed orders. A run that fails numerically becomes a row with status
// "failed: ..." rather than ending the study. Throws InputError for a study the scene cannot
// serve (unknown probe, steps that do not divide the comparison interval, ...). When `stop` asks
// during the grid, the run under way is dropped and the result says `stopped`; during the
// reference, StudyStopped is thrown.
StudyResult run_study(const StudyDef& study, const StudyLog& log = {}, const StudyStop& stop = {});

// A run of `scene` at `dt` takes no more steps to its end time than the scene's
// limits.max_steps (as `run` checks); InputError at `where` otherwise.
void check_step_count(const SceneDef& scene, double dt, const SourceLocation& where);

// The scene of a study with its overrides and end time applied.
SceneDef study_scene(const StudyDef& study);

}  // namespace periflex
