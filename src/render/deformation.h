// Deformation magnification ("warp by vector"): the strains of a stiff plate are about 1e-3, so
// its bending and a crack's opening are invisible at true scale. Each flexible body's particles
// are drawn at their rigidly moved reference position plus K times their deformation, where the
// rigid motion is the body's best-fit rotation and translation (a swinging flexible pendulum
// stays undistorted at any K). K = 1: positions as they are; K = 0: the undeformed body. Virtual
// bodies (the massless frames that tie rigid parts to particles) and the markers they carry move
// with the particles they hold; ordinary rigid bodies are drawn where they are. No GL.
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

// A rigid motion of the plane: p -> to + R(angle) (p - from).
struct RigidShift {
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  double angle = 0.0;
  bool moves = false;  // a virtual body holding particles (the others keep the identity)
  Vec2 apply(const Vec2& p) const;
};

// How each virtual body is drawn when the deformation is magnified: moved by the best-fit rigid
// motion that carries the particles it holds (SceneGeometry::particle_body) from their true
// places (the snapshot's) to their magnified ones (x, y from magnify_deformation), so the body
// and the joint markers on it stay with its particles. One entry per geometry body; identity
// for the ground, for ordinary rigid bodies (drawn where they are) and for virtual bodies that
// hold no particle.
std::vector<RigidShift> magnified_body_shifts(const Snapshot& snapshot, const std::vector<float>& x,
                                              const std::vector<float>& y);

// Where a probe is drawn when the deformation is magnified: a particle probe on its particle's
// magnified place (x, y), a probe on a virtual body moved with it (`shifts`), any other where it is.
Vec2 magnified_probe(const Snapshot::Probe& probe, const std::vector<float>& x, const std::vector<float>& y,
                     const std::vector<RigidShift>& shifts);

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
