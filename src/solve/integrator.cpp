// The integrator factory: builds the row of the catalogue (scene/integrator_catalogue.h) a name
// picks.
#include <stdexcept>

#include "core/error.h"
#include "solve/integrator.h"
#include "solve/integrator_hht.h"

namespace periflex {

// Defined beside each integrator.
std::unique_ptr<Integrator> make_symplectic_euler();
std::unique_ptr<Integrator> make_velocity_verlet();
std::unique_ptr<Integrator> make_runge_kutta4();
std::unique_ptr<Integrator> make_dormand_prince(const SolverDef& solver);

std::unique_ptr<Integrator> make_integrator(const std::string& name, const SolverDef& solver) {
  const IntegratorTraits* traits = find_integrator(name);
  if (traits == nullptr) {
    std::string choices;
    for (const auto& n : integrator_names()) choices += (choices.empty() ? "" : ", ") + n;
    throw InputError({"", 0, 0, "solver.integrator"}, "unknown integrator '" + name + "'; choose one of " + choices);
  }
  switch (traits->kind) {
    case IntegratorKind::kSymplecticEuler: return make_symplectic_euler();
    case IntegratorKind::kVerlet: return make_velocity_verlet();
    case IntegratorKind::kRk4: return make_runge_kutta4();
    case IntegratorKind::kDopri54: return make_dormand_prince(solver);
    case IntegratorKind::kHht:
      try {
        return make_hht(solver.hht_alpha);
      } catch (const std::invalid_argument& e) {
        throw InputError({"", 0, 0, "solver.hht_alpha"}, e.what());
      }
  }
  throw std::logic_error("make_integrator: a kind of the catalogue without a constructor");
}

}  // namespace periflex
