// Deformation magnification ("warp by vector"): the strains of a stiff plate are about 1e-3, so
// its bending and a crack's opening are invisible at true scale. Each flexible body's particles
// are drawn at their rigidly moved reference position plus K times their deformation, where the
// rigid motion is the body's best-fit rotation and translation (a swinging flexible pendulum
// stays undistorted at any K). K = 1: positions as they are; K = 0: the undeformed body. No GL.
#pragma once

#include <vector>

#include "solve/snapshot.h"

namespace periflex {

// Largest factor chosen automatically, and the share of a body's size its largest magnified
// deformation is brought to (as finite-element viewers do by default).
constexpr double kMaxAutoDeform = 1000.0;
constexpr double kAutoDeformShare = 0.1;

// Writes into x and y the particle positions of `snapshot` with the deformation of every
// flexible body multiplied by `factor` (>= 0). Particles of no flexible body (or a snapshot
// without reference positions) are copied as they are.
void magnify_deformation(const Snapshot& snapshot, double factor, std::vector<float>& x,
                         std::vector<float>& y);

// The largest deformation (distance from the best-fit rigid position) of any particle, each
// divided by its body's size (the diagonal of its reference bounds); 0 without particles.
double largest_relative_deformation(const Snapshot& snapshot);

// The factor that brings the largest deformation to kAutoDeformShare of its body's size,
// rounded down to 1, 2 or 5 times a power of ten, within [1, kMaxAutoDeform]: 1 for a scene
// that already deforms visibly (or has no particles).
double auto_deform_factor(const Snapshot& snapshot);

// The largest of 1, 2, 5 times a power of ten not above `value` (> 0); for factors and scale bars.
double round_down_125(double value);

}  // namespace periflex
