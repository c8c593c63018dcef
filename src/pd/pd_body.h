// A peridynamic flexible body (2D): its particles are point masses of the multibody system, their
// coordinates a contiguous slice [x0 y0 x1 y1 ...] of q that starts at coordinate_offset(). Bond
// forces enter g through ForceElement::add_forces. What a bond does is its material law's
// (material_law.h: bond-based, ordinary state-based or bilinear softening, as the material's
// `model` says); the body runs any law through the same loops.
//
// This header is the contract with the solver. Everything the solver needs is here;
// the grid, neighbour search, bond storage, laws and force kernels live in their own files.
// The body's own files: pd_body.cpp (this facade, the force evaluation), pd_body_build.cpp,
// pd_fracture.cpp, pd_body_fields.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/time_function.h"
#include "mbs/force_element.h"
#include "pd/bond_state.h"
#include "pd/bond_store.h"
#include "pd/flex_state.h"
#include "scene/scene_def.h"

namespace periflex {

class BondForceDevice;

// A particle coordinate whose motion is imposed (prescribed displacement or velocity BC).
struct PrescribedCoordinate {
  int coordinate = 0;      // global index into q
  double reference = 0.0;  // reference position of that coordinate
  TimeFunction displacement;  // q = reference + displacement(t)
};

// What one accepted step did to the bonds.
struct FractureUpdate {
  long bonds_broken = 0;          // in this update
  double energy_released = 0.0;   // strain energy the broken bonds held
  bool forces_stale = false;      // a bond broke after the last force evaluation (whose forces
                                  // still hold it): an integrator keeping them must recompute
};

class PdBody : public ForceElement {
 public:
  // Builds particles, neighbour lists and bonds. Throws InputError (with def.where) on
  // impossible input, e.g. a grid that would need more particles than allowed.
  static std::unique_ptr<PdBody> build(const FlexBodyDef& def, int coordinate_offset);
  ~PdBody() override;

  const std::string& name() const override;
  int particle_count() const;
  int coordinate_offset() const;
  // Interleaved reference positions (2 per particle), masses (1 per particle), volumes.
  const std::vector<double>& reference_positions() const;
  const std::vector<double>& masses() const;
  const std::vector<double>& volumes() const;
  // Initial velocity of each particle, interleaved.
  std::vector<double> initial_velocities() const;
  double grid_spacing() const;
  double horizon() const;
  long bond_count() const;        // intact + broken, each pair once
  long broken_bond_count() const;

  // Critical step of explicit integration, min over particles, as the law bounds it (Silling &
  // Askari 2005 for bond springs; the bound in state_based_kernel.h for the LPS).
  double critical_time_step() const;

  // ForceElement: bond forces, bond damping, global damping and loads into g.
  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                  Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;  // strain energy
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double external_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const override;
  // The force on a particle moves with its own coordinates and those of the particles it holds
  // intact bonds to; for a law that reaches further (the LPS: their dilatation), also with those
  // of their bonded neighbours.
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;

  // The law's break test at q (never in no-fail regions): breaks every bond past s0 (past s1 for
  // the softening law, whose bonds' histories grow here) that no force evaluation broke yet, and
  // reports the bonds the evaluations since the last call broke. Called once per accepted step,
  // and only when fracture is on.
  FractureUpdate update_fracture(const Eigen::VectorXd& q);
  // Bonds breaking in the force evaluation (fracture on, a law that can: bond-based): a bond past s0 at positions
  // no evaluation has seen yet (after a drift or a projection) breaks in the first evaluation that
  // sees it and takes no part in its forces, exactly as a break after the step would. The solver
  // then only collects what the evaluations broke (take_evaluation_breaks): no pass over the
  // bonds or positions on one thread between two parallel loops.
  bool breaks_in_evaluation() const;
  FractureUpdate take_evaluation_breaks();
  // A knife: breaks every intact bond whose ends, at `positions` (x0, y0, x1, y1, ... of this
  // body's particles as the caller sees them; empty: the positions at q), the segment [a, b]
  // separates, by the test a scene's notch makes at set-up. Breaks them whether fracture is on
  // or not, no-fail regions included. Reports the pairs cut and the strain energy they held at q.
  FractureUpdate cut_bonds(const Eigen::VectorXd& q, const std::vector<double>& positions, const Vec2& a,
                           const Vec2& b);
  // When a bond past s0 breaks; the solver sets it for its integrator (docs/peridynamics.md §3).
  enum class BreakTiming {
    kInEvaluation,  // in the force evaluation that first sees it, which it takes no part in (the
                    // default; integrators whose every evaluation is at accepted positions)
    kAfterStep,     // evaluations (trial stages) hold every intact bond; update_fracture breaks it
    kQuery,         // an evaluation at a state already stepped to, for a query (the joints'
                    // reactions): holds every intact bond and changes nothing in the body
  };
  void set_break_timing(BreakTiming timing);
  BreakTiming break_timing() const;
  // Evaluations at time t_end close a step and are followed by a velocity half-kick of length
  // half_kick (velocity Verlet). A bond they break takes no part in that half-kick, so the energy
  // booked for it is its strain energy there less the work it would have done over the half-kick.
  void set_step_end(double t_end, double half_kick);
  bool fracture_enabled() const;

  // Runs the bond forces (damping and the in-evaluation break test included) on `device` from now
  // on, the bonds uploaded to it here (bond_force_device.h). Only the bond-based law runs on a
  // device: throws std::invalid_argument naming the body and its law otherwise.
  void use_bond_force_device(std::unique_ptr<BondForceDevice> device);
  // The device the bond forces run on; null: the CPU loops (the default).
  const BondForceDevice* bond_force_device() const;

  // The broken bonds and the law's own fields (weighted volumes, bond histories), for saving a
  // state; a restore sets every bond's flag and stiffness from the state's bits and the model's
  // coefficients (bond_state.h), whatever broke since.
  void save_state(FlexState& out) const;
  // Throws std::invalid_argument when the state belongs to a body with other bonds.
  void restore_state(const FlexState& in);

  // Damage in [0, 1] per particle.
  void damage(std::vector<float>& out) const;
  // Largest bond stretch per particle at q (for colouring).
  void max_stretch(const Eigen::VectorXd& q, std::vector<float>& out) const;

  // Live parameters (between steps).
  void set_bond_damping(double value);
  void set_global_damping(double value);
  void set_fracture_enabled(bool enabled);
  double bond_damping() const;
  double global_damping() const;

  // Particle index nearest to a reference point.
  int nearest_particle(const Vec2& reference_point) const;
  // Particles whose reference position lies in the shape.
  std::vector<int> particles_in(const ShapeDef& region) const;
  // Imposed displacement / velocity boundary conditions as prescribed coordinates.
  std::vector<PrescribedCoordinate> prescribed_coordinates() const;

  // Intact bond pairs (i < j) for drawing small bodies; empty above max_pairs.
  void bond_pairs(std::vector<std::pair<int, int>>& out, size_t max_pairs) const;

  // Foreseeable trouble found at set-up (e.g. a Poisson ratio bond-based PD cannot
  // represent, a load region with no particles); the solver copies these into ModelInfo.
  const std::vector<std::string>& warnings() const;
  // Bond micromodulus c [N/m^6] (before influence and corrections) and critical stretch s0
  // (infinite when neither fracture_energy nor critical_stretch was given).
  double micromodulus() const;
  double critical_stretch() const;
  // The bond arrays (CSR, both directions), for tests, benchmarks and diagnostics: the model's,
  // never changed after the build; which bonds are broken now is bond_state()'s.
  const BondStore& bonds() const;
  const BondState& bond_state() const;
  // Strain energy density [J/m^3] of each particle at q, as the law defines it: (1/V_i) sum_j
  // k |xi| s^2 / 4 bond-based, the LPS energy density W_i state-based.
  void strain_energy_density(const Eigen::VectorXd& q, std::vector<double>& out) const;
  // Heap bytes held by particles and bonds.
  size_t memory_bytes() const;

  struct Impl;

 private:
  explicit PdBody(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace periflex
