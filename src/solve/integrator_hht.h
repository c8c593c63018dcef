// The implicit HHT-alpha integrator (Hilber, Hughes & Taylor 1977) for stiff problems: stiff
// peridynamic bodies whose explicit critical step is far below the step the motion needs.
//
// Scheme (Newmark updates with the HHT-weighted equation of motion, alpha in [-1/3, 0]):
//   q1 = q0 + h v0 + h^2 ((1/2 - beta) a0 + beta a1),   v1 = v0 + h ((1 - gamma) a0 + gamma a1)
//   a1 = (1 + alpha) f(t1, q1, v1) - alpha f(t0, q0, v0)
//   gamma = (1 - 2 alpha) / 2,   beta = (1 - alpha)^2 / 4
// where f = qdd(t, q, qd) is the constrained acceleration the stepper provides (forces, mass,
// and the constraint reactions of the augmented system). The unknown a1 is found by Newton
// iterations on the residual r(a1) = a1 - (1 + alpha) f(t1, q1, v1) + alpha f0, with the
// iteration matrix S = I - (1 + alpha) (beta h^2 df/dq + gamma h df/dqd). S is sparse: its
// pattern comes from the model (bonds, force elements, contacts, the constraint groups; see
// solve/jacobian_pattern.cpp) in time linear in its size, a system that cannot give it is
// perturbed once per coordinate; the columns are then coloured so that columns sharing no row
// are perturbed together (Curtis, Powell & Reid 1974), and S is factorised: the free
// coordinates' block, scaled by their masses, by sparse Cholesky when it is symmetric and the
// constrained rows read none of them, else S whole by sparse LU (solve/iteration_matrix_factors.h).
// For a peridynamic body the colours are about twice the particles within two horizons, so a
// tangent costs about a hundred force evaluations, not one per coordinate. The tangent is kept
// from step to step while Newton converges quickly, one for each of the last two step sizes (a
// run that lands on its output times alternates its dt with a shorter step).
//
// Properties: second order; unconditionally stable for linear problems; numerical damping of
// the highest frequencies grows as alpha goes from 0 (none: the trapezoidal rule) to -1/3
// (spectral radius at infinity rho_inf = (1 + alpha) / (1 - alpha)); solver.hht_alpha sets it,
// default -0.1 (rho_inf = 0.82). Pick it when a stiff part (a fine or stiff peridynamic grid) forces the
// explicit integrators to a critical step far below the time scale of interest and the
// high-frequency content is not wanted; pick an explicit integrator when the fast waves
// themselves matter (wave propagation, dynamic fracture), as large implicit steps filter them.
//
// The Newton iterations stop when the position increment falls below 1e-10 of the size of
// the configuration; after 25 iterations the step fails with a NumericalError naming the
// residual, the step, the time and the parameter to change (solver.dt).
#pragma once

#include <memory>

#include "solve/integrator.h"

namespace periflex {

// HHT-alpha with the given alpha in [-1/3, 0]. Throws std::invalid_argument outside that range.
std::unique_ptr<Integrator> make_hht(double alpha);

// "hht" with the solver definition's hht_alpha.
std::unique_ptr<Integrator> make_hht(const SolverDef& solver);

// The default of solver.hht_alpha.
constexpr double kDefaultHhtAlpha = -0.1;

}  // namespace periflex
