// The material law of a peridynamic body: what a bond's force, energy and break depend on. A
// PdBody owns one law and runs it through the loops every law shares (pd_body.cpp: forces and
// loads; pd_fracture.cpp: the break pass, the knife, saving the state; pd_body_fields.cpp: damage
// and stretch for drawing); the law answers what differs:
//   - its coefficients: what BondStore::coefficient (and so BondState::stiffness) means for it,
//     set once at build,
//   - its bond loops: forces (with its optional pre-pass, the LPS dilatation), strain energy,
//     damping power, energy density, the stable step,
//   - its break test, run once per accepted step (break_bonds), and the fields it keeps per
//     particle or per bond (the LPS weighted volumes; a softening bond's history), which it saves
//     and restores with the body's state.
// The catalogue below (make_material_law) names every law a material's `model` key can choose.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pd/bond_kernel.h"
#include "pd/bond_state.h"
#include "pd/bond_store.h"
#include "pd/flex_state.h"
#include "pd/particle_grid.h"
#include "scene/scene_def.h"

namespace periflex {

// What the build hands a law to set its bond coefficients from.
struct LawSetup {
  const FlexBodyDef& def;
  const ParticleGrid& grid;
  double micromodulus = 0.0;     // c [N/m^6]
  double horizon = 0.0;          // delta [m]
  double volume = 0.0;           // V of every particle [m^3] (the grid cell's)
  const double* volumes = nullptr;  // V_i of each particle when they differ (a graded point file); null: all V
  const std::vector<double>& k0;   // c w beta V^2 per stored direction (before any correction)
  const std::vector<double>& nx2;  // squared x-component of each stored direction's unit vector
  const uint8_t* no_fail = nullptr;  // 1: bonds at this particle never break; null when none is
  const double* modulus_ratio = nullptr;  // E_i / E of each particle (materials by block); null: all 1
};

// One force evaluation: positions and velocities of the body's particles (interleaved), the
// bond damping eta / E, the force array to add to. row_max (n entries) and pos_copy (2n), when not
// null, receive each row's largest stretch over its intact bonds and a copy of pos, for the break
// pass at the same positions.
struct LawEvaluation {
  const double* pos = nullptr;
  const double* vel = nullptr;
  double eta_over_e = 0.0;
  double* force = nullptr;
  double* row_max = nullptr;
  double* pos_copy = nullptr;
};

// What a break pass did: pairs broken and the strain energy they released (for a softening law
// also the energy its bonds dissipated while softening).
struct BreakResult {
  long pairs = 0;
  double energy = 0.0;
};

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;

  // ---- set-up
  // Critical stretch s0 where bonds start to fail (infinite: they never do).
  virtual double critical_stretch() const = 0;
  // Writes the law's coefficient of each stored direction into bonds.coefficient (and the fields
  // that follow from them). Every other call takes the store as the model's: const.
  virtual void set_coefficients(const LawSetup& setup, BondStore& bonds) = 0;
  // A stable step of explicit integration over the bonds intact in `live`, min over particles.
  virtual double critical_time_step(const BondStore& bonds, const BondState& live,
                                    const std::vector<double>& masses) const = 0;

  // ---- evaluation
  // Adds the bond forces (bond damping included) to e.force.
  virtual void add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) = 0;
  // True when the law can break bonds inside a force evaluation (add_forces_breaking).
  virtual bool breaks_in_evaluation() const { return false; }
  // As add_forces, leaving out and breaking the bonds past s0 (see add_bond_forces_breaking);
  // returns the pairs broken, energy the energy booked for them. Only when breaks_in_evaluation().
  virtual long add_forces_breaking(const BondStore& bonds, BondState& live, const LawEvaluation& e,
                                   const uint8_t* no_fail, std::vector<uint8_t>& row_broke, double half_kick,
                                   double& energy);
  // Strain energy [J], summed in a fixed order (the same bits on any thread count).
  virtual double strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const = 0;
  // Power the bond damping removes [W] (eta_over_e > 0).
  virtual double damping_power(const BondStore& bonds, const BondState& live, const double* pos,
                               const double* vel, double eta_over_e) const = 0;
  // Strain energy density [J/m^3] of each particle into out (n entries).
  virtual void energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                              const std::vector<double>& volumes, double* out) const = 0;
  // True when a particle's force depends on the particles two intact bonds away (the dilatation of
  // its neighbours), not only on those it is bonded to.
  virtual bool reaches_second_neighbours() const { return false; }

  // ---- fracture
  // The break test at accepted positions pos: breaks what the law says is broken (never at a
  // particle flagged in no_fail, which may be null); row_max, when not null, comes from a force
  // evaluation at exactly these positions.
  virtual BreakResult break_bonds(const BondStore& bonds, BondState& live, const double* pos,
                                  const uint8_t* no_fail, const double* row_max) = 0;
  // The knife broke bonds of these particles (sorted, maybe repeated).
  virtual void bonds_cut(const BondStore& bonds, const BondState& live, std::vector<int>& particles) {
    (void)bonds, (void)live, (void)particles;
  }

  // ---- state: the fields the law keeps, saved with the body's broken bonds
  virtual void save(FlexState& out) const { (void)out; }
  // False when the law's fields in `in` do not fit a body of these particles and stored directions.
  virtual bool state_fits(const FlexState& in, int particles, int64_t directed) const {
    (void)in, (void)particles, (void)directed;
    return true;
  }
  // Takes the law's fields from a state that fits.
  virtual void restore(const FlexState& in) { (void)in; }
  // Heap bytes of the law's own fields.
  virtual size_t memory_bytes() const { return 0; }
};

// Throws InputError at def.where, key "material.<key>", unless ok: for the laws' own checks.
void require_material(const FlexBodyDef& def, bool ok, const std::string& key, const std::string& message);

// Appends the warning that fracture is on but no criterion is given.
void warn_unbreakable(std::vector<std::string>& warnings);

// The critical stretch a law takes from the material: critical_stretch when given, else
// from_energy(G0) when fracture_energy is given, else infinite (with a warning when fracture is on).
template <typename FromEnergy>
double material_critical_stretch(const FlexBodyDef& def, FromEnergy&& from_energy, std::vector<std::string>& warnings) {
  const PdMaterialDef& mat = def.material;
  if (mat.critical_stretch > 0.0) return mat.critical_stretch;
  if (mat.fracture_energy > 0.0) return from_energy(mat.fracture_energy);
  if (def.fracture) warn_unbreakable(warnings);
  return std::numeric_limits<double>::infinity();
}

// The catalogue: the law the material's model names, its constants checked (InputError naming
// material.<key>) and its warnings appended.
std::unique_ptr<MaterialLaw> make_material_law(const FlexBodyDef& def, double horizon, double volume,
                                               std::vector<std::string>& warnings);

}  // namespace periflex
