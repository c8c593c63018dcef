// Plain definition structs that a scene file fills and the model is built from.
// Every field has a documented default (as Box2D's b2DefaultBodyDef does); the
// loader changes only what the scene states. docs/scenes.md documents each key.
//
// Sections:
//   ShapeDef        drawing / particle-region geometry
//   BodyDef         rigid bodies (ground, ordinary, virtual)
//   JointDef        kinematic joints (Nikravesh planar catalogue)
//   DriverDef       rheonomic constraints (imposed motion)
//   ForceDef        force elements and applied loads
//   ProbeDef        points written to series.csv
//   FlexBodyDef     peridynamic bodies (material, grid, fracture, damping, BCs)
//   AttachmentDef   rigid-flexible joints between a virtual body and particles
//   ContactDef      contact between rigid shapes and particles (scene/contact_def.h)
//   SolverDef       integrator, time step, correction, output cadence
//   LimitsDef       budgets of particles, memory, steps, rows, frames and threads
//   SceneDef        all of the above
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/time_function.h"
#include "core/vec2.h"
#include "scene/contact_def.h"
#include "scene/particle_cloud.h"

namespace periflex {

// ---------------------------------------------------------------------------
// Geometry. Used to draw rigid bodies and to fill / select particle regions.
struct ShapeDef {
  enum class Kind { kNone, kBox, kCircle, kPolygon, kBar, kBoolean };
  Kind kind = Kind::kNone;
  // kBoolean: the operands combined (scene/shape_boolean.h); difference: the first minus the others
  enum class Combine { kUnion, kDifference, kIntersection } combine = Combine::kUnion;
  std::vector<ShapeDef> operands;
  Vec2 center = Vec2::Zero();    // box and circle centre (body-fixed for rigid bodies)
  double width = 0.0, height = 0.0;  // box
  double radius = 0.0;               // circle; bar thickness / 2
  double angle = 0.0;                // box rotation about its centre
  std::vector<Vec2> vertices;        // polygon, counter-clockwise
  Vec2 p1 = Vec2::Zero(), p2 = Vec2::Zero();  // bar end points
  bool contains(const Vec2& p) const;          // inside test (bar: within radius of segment)
};

// ---------------------------------------------------------------------------
struct BodyDef {
  std::string name;
  double mass = 1.0;
  double inertia = 1.0;          // polar moment about the centre of mass
  Vec2 position = Vec2::Zero();  // centre of mass, global
  double angle = 0.0;
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;
  bool ground = false;           // fixed; has no coordinates
  bool is_virtual = false;       // a virtual body of the rigid-flexible coupling (may be massless)
  std::vector<ShapeDef> shapes;  // drawing only
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Joints of the planar catalogue. Points (s_i, s_j) and axes (u_i, u_j) are body-fixed.
struct JointDef {
  enum class Kind {
    kRevolute,              // r_i + A_i s_i - r_j - A_j s_j = 0                     (2 eq.)
    kTranslational,         // slider along u_i: perpendicularity + no relative rotation (2 eq.)
    kRigid,                 // weld: revolute + relative angle fixed                  (3 eq.)
    kRevoluteRevolute,      // massless link of fixed length between P_i and P_j      (1 eq.)
    kRevoluteTranslational  // P_j on a line through P_i along u_i, with offset       (1 eq.)
  };
  Kind kind = Kind::kRevolute;
  std::string name;
  std::string body_i, body_j;  // "ground" names the ground
  Vec2 point_i = Vec2::Zero(), point_j = Vec2::Zero();
  Vec2 axis_i = Vec2::UnitX(), axis_j = Vec2::UnitX();
  double length = 0.0;         // revolute-revolute; < 0 means "take from the initial positions"
  bool length_from_initial = true;
  double offset = 0.0;         // revolute-translational distance from the line
  double relative_angle = 0.0; // rigid: phi_j - phi_i held at this (from initial when unset)
  bool relative_angle_from_initial = true;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Drivers: Phi = coordinate(q) - f(t) = 0.
struct DriverDef {
  enum class Kind {
    kAbsoluteAngle,     // phi_i - f(t)
    kRelativeAngle,     // phi_j - phi_i - f(t)
    kAbsolutePosition,  // u . (r_i + A_i s_i) - f(t), u global axis (x or y or any)
    kRelativePosition   // u_i' . A_i^T (r_j + A_j s_j - r_i - A_i s_i) - f(t), u_i body-fixed
  };
  Kind kind = Kind::kAbsoluteAngle;
  std::string name;
  std::string body_i, body_j;
  Vec2 point_i = Vec2::Zero(), point_j = Vec2::Zero();
  Vec2 axis = Vec2::UnitX();
  TimeFunction function;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
struct ForceDef {
  enum class Kind {
    kSpringDamper,     // translational spring-damper-actuator between P_i and P_j
    kRotationalSpring, // torque k (theta - theta0) + c theta_dot between bodies (or ground)
    kForce,            // force vector f(t) * direction at a body point (global direction)
    kTorque            // torque f(t) on a body
  };
  Kind kind = Kind::kSpringDamper;
  std::string name;
  std::string body_i, body_j;
  Vec2 point_i = Vec2::Zero(), point_j = Vec2::Zero();
  double stiffness = 0.0;
  double damping = 0.0;
  double free_length = -1.0;   // < 0: taken from the initial configuration
  double free_angle = 0.0;
  bool free_angle_from_initial = true;
  TimeFunction actuator;       // spring-damper actuator force (tension positive)
  Vec2 direction = Vec2::UnitX();
  TimeFunction magnitude;      // force / torque magnitude
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// A probe is a body-fixed point of a rigid body, or the particle of a flexible
// body nearest to a reference point.
struct ProbeDef {
  std::string name;
  std::string body;            // rigid body name or flexible body name
  Vec2 point = Vec2::Zero();   // body-fixed (rigid) or reference position (flexible)
  SourceLocation where;
};

// ---------------------------------------------------------------------------
// Peridynamic bodies.
struct PdMaterialDef {
  double youngs_modulus = 0.0;   // E [Pa]
  double density = 0.0;          // rho [kg/m^3]
  double fracture_energy = 0.0;  // G0 [J/m^2]; used when critical_stretch is not given
  double critical_stretch = 0.0; // s0; > 0 overrides fracture_energy
  bool plane_strain = false;     // default plane stress
  // kBondBased: Poisson's ratio fixed by the model (1/3 plane stress, 1/4 plane strain);
  // kStateBased: ordinary state-based (LPS) with the stated poisson_ratio (docs/peridynamics.md);
  // kBilinearSoftening: bond-based whose bond force falls linearly from s0 to zero at s1, the area
  // under the curve set by fracture_energy (docs/peridynamics.md section 13)
  enum class Model { kBondBased, kStateBased, kBilinearSoftening } model = Model::kBondBased;
  // kBilinearSoftening: s1 / s0 (> 1); 0 when critical_stretch gives s0 instead
  double softening_ratio = 0.0;
  // bond-based: < 0 when not stated, otherwise checked against 1/3 or 1/4; state-based: required
  double poisson_ratio = -1.0;
};

// The material of one block of a point file's body (the file's fourth column): the particles of
// that block take these constants instead of the body's; the law, the plane and the damping stay
// the body's. A bond between two materials is as stiff as its two halves in series and breaks at
// the smaller of its ends' critical stretches (docs/scenes.md, "Materials by block").
struct BlockMaterialDef {
  long block = 0;
  double youngs_modulus = 0.0;   // E [Pa]
  double density = 0.0;          // rho [kg/m^3]
  double fracture_energy = 0.0;  // G0 [J/m^2]; used when critical_stretch is not given
  double critical_stretch = 0.0; // s0; > 0 overrides fracture_energy
  SourceLocation where;
};

// A segment cutting every bond that crosses it at set-up.
struct NotchDef {
  Vec2 p1 = Vec2::Zero(), p2 = Vec2::Zero();
};

// A boundary condition or load on the particles inside a region.
struct RegionLoadDef {
  enum class Kind {
    kPrescribedVelocity,      // v = (fx(t), fy(t)); components with no function are free
    kPrescribedDisplacement,  // u = (fx(t), fy(t))
    kTraction,                // force per unit boundary length (N/m) spread over the region's particles
    kBodyForce                // force per unit volume (N/m^3)
  };
  Kind kind = Kind::kPrescribedVelocity;
  std::string name;
  ShapeDef region;
  std::optional<TimeFunction> fx, fy;
  SourceLocation where;
};

// Largest horizon / grid spacing a flexible body may have (bonds keep their squared grid offset,
// at most (15 + 1/2)^2, in 8 bits; well beyond any useful horizon, which is 3 to 4).
constexpr double kMaxHorizonRatio = 15.0;

struct FlexBodyDef {
  std::string name;
  ShapeDef shape;                 // box, circle or polygon
  std::vector<ShapeDef> holes;
  // particles given one by one (a point file, an image): one particle at each, in this order,
  // instead of the grid that fills `shape` (then the cloud's bounding box); null otherwise
  std::shared_ptr<const ParticleCloud> particles;
  std::string geometry_source;    // where the geometry came from, for reports ("" : the scene)
  double grid_spacing = 0.0;      // dx
  double thickness = 1.0;
  double horizon_ratio = 3.0;     // m: delta = m * dx
  // each particle moved by up to jitter dx in x and in y (0 <= jitter < 0.5), the same moves for
  // the same jitter_seed: an irregular point set from any shape
  double jitter = 0.0;
  uint64_t jitter_seed = 1;
  PdMaterialDef material;
  std::vector<BlockMaterialDef> block_materials;  // other materials by block; empty: one material
  enum class Influence { kConstant, kConical } influence = Influence::kConstant;
  bool partial_volume_correction = true;
  bool surface_correction = true;
  bool fracture = true;           // false: bonds never break; stretch is never checked
  std::vector<NotchDef> notches;
  // Damage = 1 - intact / initial bond weight. kExcludeNotch: bonds a notch cut at set-up are
  // not in the initial weight (particles on the notch start undamaged); kIncludeNotch: they
  // count as broken (particles on the notch show damage from t = 0, as in most peer codes).
  enum class Damage { kExcludeNotch, kIncludeNotch } damage = Damage::kExcludeNotch;
  std::vector<ShapeDef> no_fail_regions;
  double bond_damping = 0.0;      // viscous, along the bond, proportional to stretch rate [Pa s]
  double global_damping = 0.0;    // mass-proportional, force = -alpha m v [1/s]
  Vec2 velocity = Vec2::Zero();   // initial velocity of every particle
  std::vector<RegionLoadDef> loads;
  SourceLocation where;
};

// A rigid-flexible joint: every particle of `flex_body` inside `region` moves rigidly with `body`.
struct AttachmentDef {
  std::string name;
  std::string body;               // a rigid (usually virtual) body
  std::string flex_body;
  ShapeDef region;                // global coordinates at set-up (kNone with pixels: the whole body)
  // "blue": only the particles a picture marks blue (a flexible body read from an image); "": all
  std::string pixels;
  SourceLocation where;
};

// ---------------------------------------------------------------------------
struct CorrectionDef {
  enum class Method { kNone, kBaumgarte, kProjection };
  Method method = Method::kBaumgarte;
  double alpha = 5.0;             // Baumgarte: gamma - 2 alpha Phi_dot - beta^2 Phi
  double beta = 5.0;
  double tolerance = 1e-10;       // projection: max |Phi|
  int max_iterations = 10;
};

struct SolverDef {
  std::string integrator = "rk4";  // see solve/integrator.h for the list
  double dt = 1e-3;
  double end_time = 1.0;
  double rtol = 1e-6, atol = 1e-9; // adaptive integrators
  CorrectionDef correction;
  double output_interval = 0.0;    // simulated time between series.csv rows; 0: every 10 steps
  bool auto_substep = false;       // explicit PD: sub-step when dt > safety * dt_crit
  double dt_safety = 0.8;          // fraction of the critical step allowed
  // explicit PD: a dt above the allowed step runs (to watch it diverge) instead of being refused
  bool allow_unstable = false;
  int threads = 0;                 // 0: all cores
  double hht_alpha = -0.1;         // "hht": numerical damping alpha in [-1/3, 0] (0: trapezoidal rule)
  // where the flexible bodies' bond forces run: "cpu", or "gpu" (--device overrides; docs/gpu.md)
  std::string device = "cpu";
  // the GPU's arithmetic: "fp64", or "fp32" in the displacement form (the CPU runs fp64 always)
  std::string precision = "fp64";
};

// ---------------------------------------------------------------------------
// What one run may cost. Every figure is computed before anything big is allocated and a scene
// over a limit is refused naming both; [limits] raises a limit knowingly (docs/scenes.md).
struct LimitsDef {
  double max_particles = 2e7;      // particles of all flexible bodies together
  double max_memory = 0.0;         // bytes of particles and bonds; 0: 80% of physical memory and address space
  double max_steps = 1e9;          // fixed steps of the run (end_time / dt)
  double max_output_rows = 1e6;    // series.csv rows
  double max_frames = 2e4;         // rendered frames
  double max_grid_rows = 1e7;      // grid rows scanned to place particles (rows x shapes + polygon edge rows)
  int max_threads = 0;             // solver and --threads; 0: 4 x the cores of the machine
};

// ---------------------------------------------------------------------------
struct SceneDef {
  std::string name;                // from [scene] name or the file stem
  std::string description;
  std::string path;                // file it came from
  Vec2 gravity = Vec2(0.0, -9.81);
  SolverDef solver;
  std::vector<BodyDef> bodies;     // ground is implicit; a body named "ground" is not allowed
  std::vector<JointDef> joints;
  std::vector<DriverDef> drivers;
  std::vector<ForceDef> forces;
  std::vector<ProbeDef> probes;
  std::vector<FlexBodyDef> flex_bodies;
  std::vector<AttachmentDef> attachments;
  std::vector<ContactDef> contacts;  // [[contact]] (scene/contact_def.h)
  LimitsDef limits;
  // Where single values came from, by dotted key ("solver.dt", "limits.max_memory"): the file
  // position, --set, or the command-line flag that replaced them. Checks that relate values to
  // each other name the one to change.
  std::map<std::string, SourceLocation> origin;
  // Location of `key`: its recorded origin, or the file alone.
  SourceLocation locate(const std::string& key) const {
    const auto it = origin.find(key);
    if (it != origin.end()) return it->second;
    SourceLocation where;
    where.file = path;
    where.key = key;
    return where;
  }
};

}  // namespace periflex
