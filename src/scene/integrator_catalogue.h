// The catalogue of time integrators: one row per integrator the solver has, with its name as
// written in scene files and on the command line and the traits every other part reads. The only
// place an integrator's name is spelt beside what it is: the scene reader validates names
// against it, make_integrator (solve/integrator.cpp) builds from its kind, the stepper, the scene
// budget and the studies read its traits. Adding an integrator: a row here, a case in
// make_integrator, and the class beside the others in src/solve.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace periflex {

enum class IntegratorKind { kSymplecticEuler, kVerlet, kRk4, kDopri54, kHht };

struct IntegratorTraits {
  IntegratorKind kind = IntegratorKind::kRk4;
  std::string name;               // as written in scene files (solver.integrator) and on the command line
  int order = 0;                  // global order of accuracy
  bool is_explicit = true;        // bound by the critical step of stiff (peridynamic) parts
  // a position projection after the step also corrects the velocity by the same change over
  // the step (SHAKE / RATTLE)
  bool is_symplectic = false;
  bool is_adaptive = false;       // chooses its own internal steps inside each step
  // when bonds past their critical stretch break (docs/peridynamics.md §3): in the force
  // evaluation that first sees them (integrators that evaluate only at accepted positions), or
  // after the step at the accepted positions (multi-stage integrators, whose trial stages keep
  // every intact bond)
  bool breaks_in_evaluation = false;
  // the evaluation that closes a step is followed by a velocity kick of this fraction of the
  // step (velocity Verlet's last half-kick), 0 for none
  double closing_kick = 0.0;
  // the acceleration at the end of a step is kept for the next step (its cache then holds one
  // vector, which a checkpoint file stores against an evaluation at the state)
  bool keeps_end_acceleration = false;
  // memory the scene budget counts: stage vectors per particle, and the implicit integrators'
  // tangent per stored neighbour [bytes]
  double stage_bytes_per_particle = 0.0;
  double tangent_bytes_per_neighbor = 0.0;
};

// Every integrator, in the order the choices are listed to users.
const std::vector<IntegratorTraits>& integrator_catalogue();
// The row named `name`, or nullptr when there is none.
const IntegratorTraits* find_integrator(std::string_view name);
// The row of `kind`.
const IntegratorTraits& integrator_traits(IntegratorKind kind);
// The names of the catalogue, in its order.
std::vector<std::string> integrator_names();

}  // namespace periflex
