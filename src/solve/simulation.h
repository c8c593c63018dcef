// The one object the command line, the GUI and the off-screen recorder drive:
// builds the model a scene declares, steps it, and reports samples and snapshots.
//
//   Simulation sim(scene);      // throws InputError on a scene that cannot be built
//   sim.initialize();           // consistent initial conditions (throws NumericalError)
//   while (sim.time() < end) sim.step();   // throws NumericalError with a diagnostic
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/integrator_catalogue.h"
#include "scene/scene_def.h"
#include "solve/sim_state.h"
#include "solve/snapshot.h"

namespace periflex {

// What the model contains; printed by `periflex check`, written to summary.json.
struct ModelInfo {
  int bodies = 0;                 // rigid bodies, ground excluded (virtual ones included)
  int virtual_bodies = 0;
  int joints = 0, drivers = 0, force_elements = 0, probes = 0;
  int flex_bodies = 0;
  long particles = 0, bonds = 0;
  int coordinates = 0;            // size of q
  int constraint_equations = 0;   // rows of Phi
  int redundant_equations = 0;    // rows dropped as dependent at t = 0
  std::vector<std::string> redundant_constraints;  // names of the blocks they came from
  int degrees_of_freedom = 0;     // coordinates - independent equations
  std::vector<std::string> active_modules;  // e.g. "rigid_bodies", "constraint_solver", "pd_forces"
  double critical_time_step = 0.0;          // explicit PD bound (0 when there are no particles)
  double initial_position_correction = 0.0; // size of the projection at t = 0
  double initial_velocity_correction = 0.0;
  std::vector<std::string> warnings;        // foreseeable trouble (dt above critical, ...)
};

// One row of series.csv.
struct Sample {
  double time = 0.0;
  Energies energies;
  double violation_position = 0.0;  // max |Phi|
  double violation_velocity = 0.0;  // max |Phi_q qd + Phi_t|
  long broken_bonds = 0;
  double mean_damage = 0.0, max_damage = 0.0;
  std::vector<double> probe_values; // matches Simulation::probe_columns()
  // [[contact]]: sum of the normal force magnitudes [N] and the contacts active (0 without contacts)
  double contact_force_total = 0.0;
  long contact_count = 0;
};

// Everything the GUI can change while running; applied between steps.
struct LiveSettings {
  std::string integrator;
  double dt = 0.0;
  CorrectionDef correction;
  double bond_damping = 0.0;        // applied to every flexible body
  double global_damping = 0.0;
  bool fracture = true;
  // the step may be above the explicit stability limit (solver.allow_unstable, or confirmed in
  // the window); apply() refuses such a step without it
  bool allow_unstable = false;
};

// A spring from a body point (or particle) to a point the mouse holds.
struct MouseSpring {
  int body = -1;                    // rigid body index (ground excluded: geometry index - 1), or -1
  int particle = -1;                // particle index (snapshot order), or -1
  Vec2 local_point = Vec2::Zero();  // body-fixed grab point (rigid)
  Vec2 target = Vec2::Zero();       // global
  // 0: chosen from the mass held and the scene's time scales (Simulation::set_mouse_spring)
  double stiffness = 0.0;
  // a particle grab's anchor walks to the target at a speed the material follows and its pull is
  // limited (set_mouse_spring); hard: ten times faster and stronger (Shift in the window)
  bool hard = false;
};

class Simulation {
 public:
  explicit Simulation(const SceneDef& scene);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const SceneDef& scene() const;
  const ModelInfo& info() const;

  // Projects q then qd onto the constraints at t = 0 (sizes in info()), checks the explicit
  // stability limit and records the initial energies. step() calls it when not yet called.
  void initialize();
  // One step of dt (several equal sub-steps when solver.auto_substep needs them). The time after
  // n steps is the time of the last landing plus n * dt, not a running sum.
  void step();
  // One step toward t: a step of dt, or the last one shortened to land on t exactly. Returns
  // true once the time is t (time_reached in core/sim_time.h); then it takes no step.
  bool step_toward(double t);
  // Steps of dt up to exactly t, the last one shortened to land on it.
  void advance_to(double t);
  // True when the time has reached t (the one tolerance every caller shares).
  bool reached(double t) const;
  double time() const;
  long step_count() const;
  double end_time() const;
  // The coordinates q and velocities qd as they stand (solve/sim_state.h's layout): for readers
  // that look at them in place (the Python module's arrays). Their storage stays where it is for
  // the simulation's life; only stepping and restore_state change the values.
  const Eigen::VectorXd& coordinates() const;
  const Eigen::VectorXd& velocities() const;

  std::vector<std::string> probe_columns() const;  // "probe.<name>.x", ...
  // The columns of one probe: position and velocity, and the angle and angular velocity of a
  // rigid body's point.
  static void append_probe_columns(const std::string& name, bool on_particle, std::vector<std::string>& out);
  Sample sample() const;
  // Global position of probe `index` (scene order) now: the cheap read a caller that records a
  // trajectory at every step needs (sample() computes energies and violations too).
  Vec2 probe_position(int index) const;
  void fill_snapshot(Snapshot& out) const;
  // The joints' reactions of fill_snapshot, when out.with_reactions is set (Snapshot::Reaction).
  void fill_reactions(Snapshot& out) const;

  // The whole mutable state (solve/sim_state.h): copied out, or put back so that the steps after
  // a restore repeat the steps after the save bit for bit (same settings, same thread count).
  // restore_state throws std::invalid_argument for a state of another model.
  void save_state(SimState& out) const;
  void restore_state(const SimState& in);
  // As save_state, for a file: velocity Verlet's cached end acceleration is kept as the bits it
  // differs by from the accelerations evaluated at the saved state (nearly all zero, so the
  // file is about 40 % smaller); restore_state evaluates them again and puts the cache back bit
  // for bit. The evaluation leaves nothing behind: the state is put back after it. Costs one
  // force evaluation here and one at the restore.
  void save_state_for_file(SimState& out);

  LiveSettings settings() const;
  void apply(const LiveSettings& settings);
  // Holds (or, with nullopt, releases) what the mouse grabbed. A rigid body is pulled at its
  // grab point, settling on the target within about a twentieth of the end time; a particle is
  // held with the particles within one horizon of it, each towards the target plus its offset,
  // as stiffly as the explicit step allows (so a drag deforms and can tear the body). The same
  // grab again only moves the target. Returns the total stiffness [N/m] (0: nothing held).
  double set_mouse_spring(const std::optional<MouseSpring>& spring);
  // A knife across the flexible bodies between steps (PdBody::cut_bonds): breaks the bonds the
  // segment [a, b] separates, booking their strain energy as fracture energy. drawn_x, drawn_y:
  // every particle where the caller shows it (snapshot order), so what is cut is what the eye
  // sees crossed under a magnified deformation; empty: where the particles are. Returns the pairs cut.
  long cut_bonds(const Vec2& a, const Vec2& b, const std::vector<float>& drawn_x = {},
                 const std::vector<float>& drawn_y = {});

  // Wall-clock seconds spent in each part of stepping so far, for profiling reports (forces and
  // constraints estimated from one evaluation in eight).
  struct Timing { double forces = 0, constraints = 0, integration = 0, fracture = 0; };
  Timing timing() const;

  struct Impl;

 private:
  // restore_state of a state whose cache is whole (not predicted)
  void restore_whole(const SimState& in);
  // the accelerations evaluated at `in` (save_state_for_file); the caller puts a state in place
  // after it
  void accelerations_at(const SimState& in, Eigen::VectorXd& out);
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
