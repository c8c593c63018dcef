// The mutable state of a Simulation as one plain value: everything the next step reads that
// stepping changes, and nothing the scene fixes (geometry, bond reference data, joints,
// materials stay in the model). Copying it, comparing it, saving and restoring it is what reset,
// checkpoints and the window's history rest on.
//
//   SimState s;
//   sim.save_state(s);      // after any number of steps
//   ...                     // more steps
//   sim.restore_state(s);   // the next steps repeat the ones after the save, bit for bit
//
// The live settings (integrator, dt, correction, damping, fracture switch) are not state: they
// stay as the window set them. A state restored under other settings continues under those.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "contact/contact_cache.h"
#include "pd/flex_state.h"
#include "solve/balance_drift.h"

namespace periflex {

// What an integrator keeps from one step to the next (velocity Verlet's end acceleration,
// Dormand-Prince's last stage and step size, HHT's start acceleration). Each integrator fills
// the fields it needs in an order of its own; `name` says whose they are.
struct IntegratorCache {
  std::string name;                     // the integrator that wrote it
  std::vector<double> scalars;
  std::vector<Eigen::VectorXd> vectors;
  long accepted = 0, rejected = 0;      // internal steps so far
  // vectors[0] holds the bits it differs by (XOR) from the accelerations evaluated at the state
  // (Simulation::save_state_for_file); restore_state evaluates again and puts it back whole
  bool predicted = false;
};

// The constraint rows left out as dependent (rank monitoring moves them while running).
struct RankState {
  std::vector<int> dropped, last_dependent;
  long rank_changes = 0;
};

// A passage through a singular position being watched (see Simulation's check_passage).
struct PassageWatch {
  bool open = false;
  long seen_changes = 0;
  uint64_t stable_dependent = 0;   // rows dependent outside passages
  // the largest smallest pivot of the acceleration solve so far: how well conditioned this
  // mechanism is away from its singular positions
  double best_pivot = 0.0;
  double entry_time = 0.0, entry_balance = 0.0;
  // the energy balance over the last steps outside passages (symplectic integrators with
  // projection: the integrator's own energy error a passage is judged against)
  BalanceDrift drift;
  std::vector<int> rows;           // every row left out during the passage
  // positions when it opened, to name the nearly dependent rows if the check fails (kept
  // allocated; a checkpoint holds them only while a passage is open)
  Eigen::VectorXd entry_q;
};

struct SimState {
  // the clock: time = clock_origin + clock_steps * clock_dt, or the time a step landed on
  double time = 0.0;
  long steps = 0;
  double clock_origin = 0.0, clock_dt = 0.0;
  long clock_steps = 0;
  bool initialized = false;
  // rigid coordinates (x, y, phi per body) then particle coordinates (x, y per particle)
  Eigen::VectorXd q, qd;
  // energy accounts: the integrals of dissipated, external and driver power, fracture energy,
  // and the references of the balance and of the divergence check
  Eigen::Vector3d work = Eigen::Vector3d::Zero();
  double fracture_energy = 0.0;
  long broken_bonds = 0;
  double initial_total = 0.0, initial_gravity = 0.0, energy_scale = 0.0;
  double initial_position_correction = 0.0, initial_velocity_correction = 0.0;
  PassageWatch passage;
  RankState rank;
  IntegratorCache integrator;
  std::vector<FlexState> flex;          // per flexible body, model order
  std::vector<ContactCache> contacts;   // per contact, model order (empty caches for rigid ones)
};

// Heap bytes a state holds (for the window's memory budget).
size_t state_bytes(const SimState& state);

}  // namespace periflex
