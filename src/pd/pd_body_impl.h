// Internal to the PdBody files (pd_body.cpp: the facade and the force evaluation;
// pd_body_build.cpp: particles, bonds and loads from a FlexBodyDef; pd_fracture.cpp: breaking bonds
// and the state; pd_body_fields.cpp: per-particle fields): what a body holds.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/time_function.h"
#include "pd/bond_force_device.h"
#include "pd/bond_state.h"
#include "pd/bond_store.h"
#include "pd/material_law.h"
#include "pd/particle_grid.h"
#include "pd/pd_body.h"

namespace periflex {

// A traction or body force: force on each listed particle = scale * (fx(t), fy(t)).
struct AppliedLoad {
  std::vector<int> particles;
  double scale = 0.0;
  std::optional<TimeFunction> fx, fy;
  std::vector<double> weights;  // per listed particle, times scale (a body force on unequal volumes); empty: 1
};

// True when the bond [a, b] crosses the notch [c, d] (pd_body_build.cpp; the knife makes the same test).
bool notch_cuts_bond(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tolerance);

struct PdBody::Impl {
  FlexBodyDef def;
  int offset = 0;
  ParticleGrid grid;
  std::vector<double> reference, mass, volume;
  BondStore bonds;                       // the model's: written by the build alone
  BondState live;                        // what breaking changes (each bond's stiffness and flag)
  std::vector<uint8_t> no_fail;          // 1: bonds at this particle never break
  std::vector<double> initial_weight;    // sum of partial-volume factors of the initial bonds
  std::vector<double> class_weight;      // partial-volume factor per bond length class (on the grid)
  std::vector<double> bond_weight;       // partial-volume factor per stored direction (off the grid)
  double dx = 0.0, delta = 0.0, c = 0.0, s0 = 0.0;
  bool fracture = false;
  double bond_damping = 0.0, global_damping = 0.0;
  long broken_pairs = 0;
  // the material law: what bonds.coefficient means, the bond loops, the break test (material_law.h)
  std::unique_ptr<MaterialLaw> law;
  std::vector<PrescribedCoordinate> prescribed;
  std::vector<AppliedLoad> loads;
  std::vector<std::string> warnings;

  // the row maxima of the stretch, found by the last force evaluation, and the positions they
  // belong to: update_fracture at the same positions (the usual case) skips its own pass
  std::vector<double> stretch_cache_pos, stretch_cache_most;
  bool stretch_cache_valid = false;
  bool tracks_stretch() const { return fracture && std::isfinite(s0); }
  PdBody::BreakTiming break_timing = PdBody::BreakTiming::kInEvaluation;
  double step_end = std::numeric_limits<double>::quiet_NaN(), half_kick = 0.0;
  std::vector<uint8_t> row_broke;   // per particle: a bond of the row broke in this evaluation
  long pending_broken = 0;          // broken by force evaluations since update_fracture
  double pending_energy = 0.0;

  // bonds break inside the force evaluation (the law can, and the timing asks for it)
  bool breaks_in_evaluation() const {
    return tracks_stretch() && law->breaks_in_evaluation() && break_timing == PdBody::BreakTiming::kInEvaluation;
  }
  // where the bond forces run when not on the CPU (null: CPU); told of every change to the bonds
  // made outside its evaluations
  std::unique_ptr<BondForceDevice> device;
  void bonds_changed_on_host() {
    if (device) device->bonds_changed();
  }

  const uint8_t* no_fail_flags() const { return def.no_fail_regions.empty() && !def.particles ? nullptr : no_fail.data(); }
  const double* pos(const Eigen::VectorXd& q) const { return q.data() + offset; }
  int n() const { return grid.size(); }
};

// The bond forces of the body on its device (pd_body_device.cpp): as the law's add_forces or
// add_forces_breaking for the three cases PdBody::add_forces distinguishes.
void add_device_bond_forces(PdBody::Impl& m, const LawEvaluation& e, double t);

}  // namespace periflex
