// A PdBody whose bond forces run on a device (bond_force_device.h): choosing it at set-up, and the
// force pass in the three forms the CPU path has (breaking in the evaluation; holding every bond
// and keeping the row maxima for the break pass after the step; elastic and damped only).
#include <algorithm>
#include <stdexcept>

#include "pd/bond_kernel.h"
#include "pd/pd_body_impl.h"

namespace periflex {

void PdBody::use_bond_force_device(std::unique_ptr<BondForceDevice> device) {
  Impl& m = *impl_;
  // the device runs the bond-based law's formulas only
  if (m.def.material.model != PdMaterialDef::Model::kBondBased)
    throw std::invalid_argument("flexible body '" + m.def.name +
                                "': only the bond-based law (material.model = \"bond_based\") runs on the GPU");
  if (device) device->upload(m.bonds, m.live, m.no_fail_flags(), m.reference.data());
  m.device = std::move(device);
  m.stretch_cache_valid = false;
}

const BondForceDevice* PdBody::bond_force_device() const { return impl_->device.get(); }

void add_device_bond_forces(PdBody::Impl& m, const LawEvaluation& law_eval, double t) {
  DeviceEvaluation e;
  e.pos = law_eval.pos;
  e.vel = law_eval.vel;
  e.eta_over_e = law_eval.eta_over_e;
  e.force = law_eval.force;
  if (m.breaks_in_evaluation()) {
    // as BondBasedLaw::add_forces_breaking: the device leaves out and marks the bonds past s0, the
    // host settles them (energy booked, stiffness zeroed) in row order
    m.stretch_cache_valid = false;
    m.row_broke.resize(m.n(), 0);
    e.breaking = true;
    e.s0 = m.s0;
    e.row_broke = m.row_broke.data();
    m.device->add_forces(m.bonds, m.live, e);
    double energy = 0.0;
    const double half_kick = t == m.step_end ? m.half_kick : 0.0;
    const long broken = settle_broken_bonds(m.bonds, m.live, e.pos, e.vel, half_kick, m.row_broke.data(), energy);
    m.pending_broken += broken;
    m.pending_energy += energy;
    m.broken_pairs += broken;
  } else if (m.tracks_stretch() && m.break_timing != PdBody::BreakTiming::kQuery) {
    // bonds break after the step (update_fracture), from these row maxima at these positions
    m.stretch_cache_pos.assign(e.pos, e.pos + 2 * m.n());
    m.stretch_cache_most.resize(m.n());
    m.stretch_cache_valid = true;
    e.row_max = m.stretch_cache_most.data();
    m.device->add_forces(m.bonds, m.live, e);
  } else {
    m.device->add_forces(m.bonds, m.live, e);
  }
}

}  // namespace periflex
