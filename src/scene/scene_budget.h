// The cost of running a scene, computed before anything big is allocated, against the scene's
// [limits]: particles (counted exactly, by the scan that later fills them), bonds, bytes of
// memory for all flexible bodies together, steps, series.csv rows, rendered frames and threads.
// It also checks the values that only make sense together: dt against end_time, the output and
// frame interval against dt. A scene over a limit is refused with InputError naming the figure,
// the limit and the key (or command-line flag) to change.
//
//   RunPlan plan;                       // what the command line adds
//   plan.frame_every = 0.01;
//   const SceneBudget budget = check_scene_budget(scene, plan);
#pragma once

#include <string>

#include "core/error.h"
#include "scene/scene_def.h"

namespace periflex {

// What a command adds to the scene's own cost.
struct RunPlan {
  double frame_every = 0.0;       // simulated seconds between rendered frames; 0: no frames
  bool frame_every_given = false; // typed by the user (only then may it be shorter than dt)
  SourceLocation frame_every_where;
  int threads = 0;                // --threads; 0: not given
  SourceLocation threads_where;
};

// The figures checked, for reports and tests.
struct SceneBudget {
  double particles = 0.0;   // all flexible bodies, exact
  double bonds = 0.0;       // an upper bound: particles x neighbours within the reach / 2
  double memory = 0.0;      // bytes at the run's peak (program, particles, bonds, integrator)
  double steps = 0.0;       // whole steps of dt to end_time (fixed-step integrators), at least
  double rows = 0.0;        // series.csv rows, exact
  double frames = 0.0;      // rendered frames, exact
};

// Peak memory of a run, fitted to the peak resident memory `/usr/bin/time` measures (2 cores,
// Release build) on the notched plate, glass_branching and a 120 000-particle sliver two
// particles thick (tests/data/scenes/thin_sliver.toml), whose neighbour counts per particle are
// 34, 35 and 13: the program itself, then per particle and per stored neighbour (each bond held
// from both ends) with the neighbours counted exactly. The integrators keep stage vectors
// (per particle) and the implicit ones a sparse tangent and its factors (per neighbour).
// The program's own 12 MB include CHOLMOD, OpenBLAS and the Fortran run-time they load
// (`periflex --version` holds 10.5 MB against 7.3 MB without them; the flexible pendulum's
// short run peaks at 12.9 MB).
constexpr double kProgramBytes = 12e6;
constexpr double kBytesPerParticle = 64.0;
constexpr double kBytesPerNeighbor = 34.0;
// A body off the grid keeps each stored neighbour's own 1 / |xi| and partial volume (pd/bond_store.h).
constexpr double kBytesPerNeighborOffGrid = 16.0;
// Stage vectors of an integrator, per particle, and the implicit integrators' tangent, per stored
// neighbour, from the integrator catalogue (0 for a name it lacks).
double integrator_bytes_per_particle(const std::string& integrator);
double integrator_bytes_per_neighbor(const std::string& integrator);
// The iteration matrices an implicit integrator keeps (one per step size, see
// solve/integrator_hht.h): two when the steps are cut at the output times (output_interval not
// a whole number of dt), one otherwise.
int iteration_matrices(const SolverDef& solver);

// Cores of this machine (at least 1).
int machine_cores();
// The largest thread count accepted: limits.max_threads, or 4 x the cores.
int thread_cap(const LimitsDef& limits);
// The memory budget in bytes: limits.max_memory, or the smaller of 80% of physical memory and
// half the address-space limit of this process.
double memory_cap(const LimitsDef& limits);

// Checks the scene (and the plan) against its limits; throws InputError. Returns the figures.
SceneBudget check_scene_budget(const SceneDef& scene, const RunPlan& plan = {});

}  // namespace periflex
