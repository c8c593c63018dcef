// The scene's settings sections: [scene] (name, description, gravity), [solver] with
// [solver.correction], and [limits] (the budgets raised or lowered knowingly).
#include "scene/scene_table_reader.h"

#include <algorithm>

#include "scene/scene_loader.h"

namespace periflex {

void SceneTableReader::read_scene(const std::string& default_name) {
  const toml::table* table = top_.optional_table("scene");
  scene_.name = default_name;
  if (table == nullptr) return;
  TableReader in(context_, *table, "scene", "[scene]");
  scene_.name = in.string("name", default_name);
  if (scene_.name.empty()) in.fail("name", "the scene name may not be empty (omit it to use the file name)");
  // the name titles outputs and (made safe) names the default output folder: one short line
  if (scene_.name.size() > kMaxSceneNameLength)
    in.fail("name", "the scene name has " + std::to_string(scene_.name.size()) + " characters; at most " +
            std::to_string(kMaxSceneNameLength) + " are allowed");
  if (std::any_of(scene_.name.begin(), scene_.name.end(), [](char c) { return static_cast<unsigned char>(c) < ' ' || c == 127; }))
    in.fail("name", "the scene name may not contain control characters (line breaks, tabs, ...)");
  scene_.description = in.string("description", "");
  scene_.gravity = in.vec2("gravity", Vec2(0.0, -9.81));
  in.finish();
}

void SceneTableReader::read_solver() {
  const toml::table* table = top_.optional_table("solver");
  if (table == nullptr) return;
  TableReader in(context_, *table, "solver", "[solver]");
  SolverDef& solver = scene_.solver;
  // values that later checks relate to each other (and to command-line flags) remember where they came from
  for (const char* key : {"integrator", "dt", "end_time", "output_interval", "threads", "device", "precision"})
    note_origin(in, key);
  solver.integrator = in.choice("integrator", scene_integrator_names(), solver.integrator);
  solver.dt = in.number("dt", solver.dt, Sign::kPositive, true);
  solver.end_time = in.number("end_time", solver.end_time, Sign::kPositive, true);
  if (solver.dt > solver.end_time)
    in.fail(in.has("dt") ? "dt" : "end_time", "dt = " + format_number(solver.dt) + " exceeds end_time = " +
            format_number(solver.end_time) + "; the run would not take a single step");
  solver.rtol = in.number("rtol", solver.rtol, Sign::kPositive);
  solver.atol = in.number("atol", solver.atol, Sign::kPositive);
  solver.output_interval = in.number("output_interval", solver.output_interval, Sign::kNonNegative, true);
  solver.auto_substep = in.boolean("auto_substep", solver.auto_substep);
  solver.dt_safety = in.number("dt_safety", solver.dt_safety, Sign::kPositive);
  if (solver.dt_safety > 1.0)
    in.fail("dt_safety", "must be in (0, 1] (a fraction of the critical step), found " + format_number(solver.dt_safety));
  solver.allow_unstable = in.boolean("allow_unstable", solver.allow_unstable);
  if (solver.allow_unstable && solver.auto_substep)
    in.fail("allow_unstable", "cannot be true with auto_substep = true (sub-steps keep every step stable); "
                              "set one of them");
  solver.threads = static_cast<int>(in.integer("threads", solver.threads, 0));
  solver.device = in.choice("device", {"cpu", "gpu"}, solver.device);
  solver.precision = in.choice("precision", {"fp64", "fp32"}, solver.precision);
  // HHT-alpha is unconditionally stable only for alpha in [-1/3, 0]
  solver.hht_alpha = in.number("hht_alpha", solver.hht_alpha);
  if (solver.hht_alpha < -1.0 / 3.0 || solver.hht_alpha > 0.0)
    in.fail("hht_alpha", "must be in [-1/3, 0], found " + format_number(solver.hht_alpha));
  if (const toml::table* correction = in.optional_table("correction")) read_correction(*correction);
  in.finish();
}

// Records where the value under `key` of `in` came from (file position or --set).
void SceneTableReader::note_origin(TableReader& in, const char* key) {
  if (const toml::node* node = in.table().get(key)) scene_.origin[in.key_path(key)] = context_.locate(node, in.key_path(key));
}

// [limits]: budgets raised (or lowered) knowingly
void SceneTableReader::read_limits() {
  const toml::table* table = top_.optional_table("limits");
  if (table == nullptr) return;
  TableReader in(context_, *table, "limits", "[limits]");
  LimitsDef& l = scene_.limits;
  for (const char* key : {"max_particles", "max_memory", "max_steps", "max_output_rows", "max_frames",
                          "max_grid_rows", "max_threads"})
    note_origin(in, key);
  l.max_particles = in.number("max_particles", l.max_particles, Sign::kPositive);
  l.max_memory = in.number("max_memory", l.max_memory, Sign::kNonNegative);
  l.max_steps = in.number("max_steps", l.max_steps, Sign::kPositive);
  l.max_output_rows = in.number("max_output_rows", l.max_output_rows, Sign::kPositive);
  l.max_frames = in.number("max_frames", l.max_frames, Sign::kPositive);
  l.max_grid_rows = in.number("max_grid_rows", l.max_grid_rows, Sign::kPositive);
  l.max_threads = static_cast<int>(in.integer("max_threads", l.max_threads, 0));
  // a limit is a count: even raised knowingly it must fit the integers that hold it
  for (const char* key : {"max_particles", "max_steps", "max_output_rows", "max_frames", "max_grid_rows"})
    if (const auto value = in.optional_number(key); value && *value > 1e15)
      in.fail(key, "must be at most 1e15, found " + format_number(*value));
  if (l.max_particles > 2e9) in.fail("max_particles", "must be at most 2e9 (particle indices are 32-bit integers)");
  in.finish();
}

void SceneTableReader::read_correction(const toml::table& table) {
  TableReader in(context_, table, "solver.correction", "[solver.correction]");
  CorrectionDef& c = scene_.solver.correction;
  const std::string method = in.choice("method", {"none", "baumgarte", "projection"}, "baumgarte");
  c.method = method == "none" ? CorrectionDef::Method::kNone
             : method == "projection" ? CorrectionDef::Method::kProjection : CorrectionDef::Method::kBaumgarte;
  c.alpha = in.number("alpha", c.alpha, Sign::kNonNegative);
  c.beta = in.number("beta", c.beta, Sign::kNonNegative);
  c.tolerance = in.number("tolerance", c.tolerance, Sign::kPositive);
  c.max_iterations = static_cast<int>(in.integer("max_iterations", c.max_iterations, 1));
  // each step runs up to this many Newton iterations: a million would stall every step
  if (c.max_iterations > kMaxProjectionIterations)
    in.fail("max_iterations", "must be at most " + std::to_string(kMaxProjectionIterations) + ", found " +
            std::to_string(c.max_iterations) + " (projection converges in a few iterations or not at all)");
  in.finish();
}

}  // namespace periflex
