// The spatial side of a flexible body's accuracy: a quantity with a known answer, measured as
// the particle grid is refined and as the horizon ratio m = delta / dx changes.
//
//   wave_speed            a bar clamped at one end, every particle given the same initial axial
//                         velocity: the wave that stops the bar at the clamp reaches the free end
//                         at t = L / c and reverses the tip there, against c = sqrt(E / rho)
//                         (plane stress, thin strip).
//   cantilever_frequency  a cantilever released from rest under gravity: its tip reaches its
//                         lowest point after half a period of the first bending mode, against the
//                         Euler-Bernoulli f1 = (1.8751^2 / (2 pi L^2)) sqrt(E I / (rho A)).
//
// L runs from the clamped region's far edge to the free end; the beam lies along x, clamped on
// its left by a prescribed_displacement load.
#pragma once

#include "study/study_runner.h"

namespace periflex {

// Runs every (grid_spacing, horizon_ratio) pair of study.refine, each at half the explicit
// critical step of its grid (or at the [[method]]'s dt, scaled with the grid, when one is given).
// When `stop` asks, the run under way is dropped and the result says `stopped`.
StudyResult run_refine_study(const StudyDef& study, const StudyLog& log = {}, const StudyStop& stop = {});

// The time of the first interior extreme (a minimum when `minimum`) of a sampled signal, refined
// by the parabola through the extreme sample and its neighbours; negative when there is none.
double first_extreme_time(const std::vector<double>& times, const std::vector<double>& values, bool minimum);

}  // namespace periflex
