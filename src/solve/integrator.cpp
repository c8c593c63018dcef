// The integrator registry: names as written in scene files, and the factory.
#include <stdexcept>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "solve/integrator.h"
#include "solve/integrator_hht.h"

namespace periflex {

// Defined beside each integrator.
std::unique_ptr<Integrator> make_symplectic_euler();
std::unique_ptr<Integrator> make_velocity_verlet();
std::unique_ptr<Integrator> make_runge_kutta4();
std::unique_ptr<Integrator> make_dormand_prince(const SolverDef& solver);

// the scene schema owns the list, so a name it accepts is one make_integrator builds
std::vector<std::string> integrator_names() { return scene_integrator_names(); }

std::unique_ptr<Integrator> make_integrator(const std::string& name, const SolverDef& solver) {
  if (name == "symplectic_euler") return make_symplectic_euler();
  if (name == "verlet") return make_velocity_verlet();
  if (name == "rk4") return make_runge_kutta4();
  if (name == "dopri54") return make_dormand_prince(solver);
  if (name == "hht") {
    try {
      return make_hht(solver.hht_alpha);
    } catch (const std::invalid_argument& e) {
      throw InputError({"", 0, 0, "solver.hht_alpha"}, e.what());
    }
  }
  std::string choices;
  for (const auto& n : integrator_names()) choices += (choices.empty() ? "" : ", ") + n;
  throw InputError({"", 0, 0, "solver.integrator"}, "unknown integrator '" + name + "'; choose one of " + choices);
}

}  // namespace periflex
