// A self-contained copy of what is drawn: the renderer, the GUI panels and the frame
// writers read only this, never the solver's internals. Filled by Simulation::fill_snapshot
// between steps; copying it is the only synchronisation the render thread needs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "model/marker_kind.h"
#include "scene/scene_def.h"

namespace periflex {

// What does not change during a run: set once when the model is built.
struct SceneGeometry {
  std::string scene_name;
  struct Body {
    std::string name;
    bool ground = false;
    bool is_virtual = false;
    std::vector<ShapeDef> shapes;  // body-fixed
  };
  std::vector<Body> bodies;        // index 0 is the ground
  struct FlexBody {
    std::string name;
    int first_particle = 0;        // into the particle arrays of Snapshot
    int particle_count = 0;
    double grid_spacing = 0.0;     // disc diameter when drawn
  };
  std::vector<FlexBody> flex_bodies;
  std::vector<uint8_t> particle_attached;  // 1 where a rigid-flexible joint holds the particle
  // the body (index into `bodies`) whose rigid-flexible joint holds each particle, 0 for none
  // (the drawing moves a virtual body with its particles when deformation is magnified)
  std::vector<int> particle_body;
  std::vector<float> reference_x, reference_y;
  // the same in full precision (x0, y0, x1, y1, ...), and each particle's volume [m^3]: for the
  // writers, whose displacements must not lose digits to float
  std::vector<double> reference_xy;
  std::vector<double> particle_volume;
  std::vector<uint16_t> bonds_initial;     // bonds of each particle at the start (for inspection)
  Vec2 bounds_min = Vec2::Zero(), bounds_max = Vec2::Zero();  // of the initial configuration
  bool has_particles() const { return !reference_x.empty(); }
};

struct Energies {
  double kinetic = 0.0;
  double potential_gravity = 0.0;
  double potential_elastic = 0.0;  // springs + PD strain energy
  double dissipated = 0.0;         // damping, accumulated
  double fracture = 0.0;           // strain energy released by broken bonds, accumulated
  double external_work = 0.0;      // applied loads and actuators, accumulated
  double driver_work = 0.0;        // work of rheonomic constraints, accumulated
  // kinetic + potential + dissipated + fracture - external_work - driver_work - (same at t = 0)
  double balance = 0.0;
};

struct Snapshot {
  std::shared_ptr<const SceneGeometry> geometry;
  double time = 0.0;
  long step = 0;

  struct Pose {
    double x = 0.0, y = 0.0, angle = 0.0;
    double vx = 0.0, vy = 0.0, omega = 0.0;  // their rates
  };
  std::vector<Pose> bodies;        // same order as geometry->bodies (ground first)

  // Particles of all flexible bodies, concatenated in geometry order.
  std::vector<float> px, py;
  std::vector<float> damage;       // [0, 1]
  std::vector<float> displacement; // |x - X|
  std::vector<float> speed;        // |v|
  std::vector<float> vx, vy;       // velocity components
  std::vector<float> strain;       // largest bond stretch
  std::vector<uint16_t> bonds_intact;  // bonds of each particle not broken (of geometry->bonds_initial)
  std::vector<std::pair<int, int>> bond_pairs;  // intact bonds, only for small bodies
  // Positions and velocities in full precision (x0, y0, x1, y1, ...), filled only when the
  // caller sets full_precision (the VTK writer); the drawing needs floats only.
  bool full_precision = false;
  std::vector<double> particle_q, particle_qd;

  struct Marker {
    using Kind = MarkerKind;
    Kind kind = Kind::kRevolute;
    Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // one point, or two for links and sliders
    int body_a = 0, body_b = 0;  // the bodies (geometry indices, 0 the ground) carrying a and b
  };
  std::vector<Marker> markers;
  struct Spring { Vec2 a = Vec2::Zero(), b = Vec2::Zero(); };
  std::vector<Spring> springs;
  // particle: a particle probe's index in px, py (-1: a rigid probe); body: a rigid probe's
  // body as the markers count it (0: ground), so the drawing can move it with what carries it
  struct Probe {
    std::string name;
    Vec2 position = Vec2::Zero();
    int particle = -1;
    int body = 0;
  };
  std::vector<Probe> probes;

  // Active contacts: where each acts and the force on its first side [N] (the particle, the
  // first particle of a pair, body_i). Empty without [[contact]].
  struct Contact { Vec2 point = Vec2::Zero(), force = Vec2::Zero(); };
  std::vector<Contact> contacts;
  Energies energies;
  double violation_position = 0.0;
  double violation_velocity = 0.0;
  long broken_bonds = 0;
  double max_damage = 0.0;

  // What the mouse holds (Simulation::set_mouse_spring): the anchor the spring pulls towards,
  // which walks to the pointer at a capped speed in simulated time, the spring's pull now and
  // the limits of the grip. held is false when the mouse holds nothing.
  struct MouseGrip {
    bool held = false;
    Vec2 anchor = Vec2::Zero(), target = Vec2::Zero();
    double force = 0.0;      // [N] stiffness times the anchor's lead on what is held
    double max_force = 0.0;  // [N] the anchor waits while the pull is above it (0: no limit)
    double max_speed = 0.0;  // [m/s] of the anchor in simulated time (0: it jumps to the pointer)
  };
  MouseGrip mouse;

  // One row of series.csv at this instant (output/series_row.h) and its column names, for the
  // window's plots: filled by the window's model only, empty elsewhere.
  std::shared_ptr<const std::vector<std::string>> series_columns;
  std::vector<double> series;

  // The joints' and drivers' reactions at this instant: the Lagrange multipliers as the force
  // and moment -Phi_q^T lambda they apply to each rigid body they hold, the moment about the
  // body's reference point. Filled only when the caller sets with_reactions (it costs a
  // solve of the equations of motion).
  struct Reaction {
    std::string joint;
    int body = 0;                  // geometry index (0: ground is never listed)
    double fx = 0.0, fy = 0.0;     // [N]
    double moment = 0.0;           // [N m]
  };
  bool with_reactions = false;
  std::vector<Reaction> reactions;
};

}  // namespace periflex
