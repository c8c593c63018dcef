#include "cli/scene_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/resources.h"
#include "scene/scene_loader.h"
#include "scene/scene_warnings.h"
#include "scene/toml_reader.h"
#include "solve/simulation.h"

namespace periflex {

SourceLocation flag_location(const std::string& flag) { return {"command line", 0, 0, flag}; }

SceneDef load_scene_with_options(const std::string& path, const std::vector<std::string>& overrides,
                                 std::optional<double> until, std::optional<double> dt,
                                 std::optional<std::string> integrator, const RunPlan& plan) {
  SceneDef scene = load_scene(path, overrides);
  auto option_error = [](const std::string& option, const std::string& what) {
    return InputError(flag_location(option), what);
  };
  // a time from the command line obeys the scene's rules for times; the flag then owns the key
  auto time_flag = [&](const std::string& flag, double value, const char* what) {
    if (!std::isfinite(value) || value <= 0)
      throw option_error(flag, std::string("expected a positive ") + what + ", found " + format_number(value));
    if (value > kMaxGeometricMagnitude)
      throw option_error(flag, "value " + format_number(value) + " is absurdly large (the limit for times is " +
                                   format_number(kMaxGeometricMagnitude) + ")");
  };
  if (until) {
    time_flag("--until", *until, "end time");
    scene.solver.end_time = *until;
    scene.origin["solver.end_time"] = flag_location("--until");
  }
  if (dt) {
    time_flag("--dt", *dt, "time step");
    scene.solver.dt = *dt;
    scene.origin["solver.dt"] = flag_location("--dt");
  }
  if (integrator) {
    scene.solver.integrator = *integrator;
    scene.origin["solver.integrator"] = flag_location("--integrator");
  }

  // the integrators this program has, wherever the name came from (file, --set or --integrator)
  const auto names = integrator_names();
  if (std::find(names.begin(), names.end(), scene.solver.integrator) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(scene.locate("solver.integrator"),
                     "integrator '" + scene.solver.integrator + "' is not available in this program; expected one of: " + list);
  }

  // values against each other and the whole scene against its limits, before anything is built
  check_scene_budget(scene, plan);
  for (const std::string& warning : scene_warnings(scene)) std::fprintf(stderr, "periflex: %s\n", warning.c_str());
  return scene;
}

std::string default_scene_path() { return find_resource_root() + "/scenes/notched_plate.toml"; }

}  // namespace periflex
