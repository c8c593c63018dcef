#include "cli/scene_setup.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/resources.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {

SceneDef load_scene_with_options(const std::string& path, const std::vector<std::string>& overrides,
                                 std::optional<double> until, std::optional<double> dt,
                                 std::optional<std::string> integrator) {
  SceneDef scene = load_scene(path, overrides);
  auto option_error = [](const std::string& option, const std::string& what) {
    return InputError({"command line", 0, 0, option}, what);
  };
  if (until) {
    if (!std::isfinite(*until) || *until <= 0) throw option_error("--until", "expected a positive time");
    scene.solver.end_time = *until;
  }
  if (dt) {
    if (!std::isfinite(*dt) || *dt <= 0) throw option_error("--dt", "expected a positive time step");
    scene.solver.dt = *dt;
  }
  if (integrator) {
    const auto names = integrator_names();
    if (std::find(names.begin(), names.end(), *integrator) == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw option_error("--integrator", "unknown integrator '" + *integrator + "'; expected one of: " + list);
    }
    scene.solver.integrator = *integrator;
  }
  return scene;
}

std::string default_scene_path() { return find_resource_root() + "/scenes/notched_plate.toml"; }

}  // namespace periflex
