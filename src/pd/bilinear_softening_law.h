// A bond-based law with bilinear softening, for quasi-brittle materials (concrete, rock): a bond's
// force k s rises linearly to the critical stretch s0, then falls linearly to zero at the final
// stretch s1 (k the bond-based spring stiffness, s the stretch). The area under the curve sets the
// fracture energy G0: s0 s1 = sc^2, sc the brittle critical stretch of the same G0
// (critical_stretch_from_energy), so either s0 = sc / sqrt(r), s1 = sc sqrt(r) from a stated ratio
// r = s1 / s0, or s1 = sc^2 / s0 from a given s0 (docs/peridynamics.md derives it).
//
// Damage is irreversible: each stored bond direction keeps the largest stretch h it has reached,
// a history field of the body's state (both copies of a bond see the same stretch bit for bit and
// hold the same h). A bond past s0 unloads and reloads along the secant to the origin,
// f = k s omega(h), omega(h) = s0 (s1 - h) / (h (s1 - s0)); compression is never softened. The
// history grows once per accepted step (break_bonds), so trial stages follow the same curve and the
// energy ledger stays exact: the strain energy is the integral of the force at the committed
// history, and what raising h takes out of it is booked as fracture energy. A bond breaks when h
// reaches s1. Bonds at a no-fail particle stay linear.
#pragma once

#include <string>
#include <vector>

#include "pd/material_law.h"

namespace periflex {

// The two stretches of the curve.
struct SofteningStretches {
  double s0 = 0.0;  // end of the linear rise (peak force k s0)
  double s1 = 0.0;  // force back to zero: the bond breaks
};

// s0 and s1 from G0 and either the ratio r = s1 / s0 (> 1; critical_stretch <= 0) or s0 itself
// (critical_stretch > 0, below sc): s0 s1 = sc^2 with sc = critical_stretch_from_energy(G0, ...).
SofteningStretches softening_stretches(double fracture_energy, double softening_ratio, double critical_stretch,
                                       double youngs_modulus, double horizon, bool plane_strain,
                                       FlexBodyDef::Influence kind);

// Energy of one bond per unit k |xi| at stretch s with history h (the integral of its force f / k
// from 0 to s with h held): s^2 / 2 below s0, the softening curve's area beyond.
double softening_bond_energy(double s, double h, const SofteningStretches& curve);

class BilinearSofteningLaw : public MaterialLaw {
 public:
  // Needs fracture_energy and one of softening_ratio or critical_stretch (InputError naming the key).
  BilinearSofteningLaw(const FlexBodyDef& def, double horizon, std::vector<std::string>& warnings);

  double critical_stretch() const override { return curve_.s0; }
  double final_stretch() const { return curve_.s1; }
  // The bond-based spring stiffness (surface correction included); history 0, no-fail flags kept.
  void set_coefficients(const LawSetup& setup, BondStore& bonds) override;
  double critical_time_step(const BondStore& bonds, const BondState& live,
                            const std::vector<double>& masses) const override;

  void add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) override;
  double strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const override;
  double damping_power(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                       double eta_over_e) const override;
  void energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                      const std::vector<double>& volumes, double* out) const override;

  // Raises the history of every bond past s0 and past its h to its stretch, books the energy that
  // takes out of the bond, and breaks the bonds that reached s1.
  BreakResult break_bonds(const BondStore& bonds, BondState& live, const double* pos, const uint8_t* no_fail,
                          const double* row_max) override;

  void save(FlexState& out) const override { out.bond_history = history_; }
  bool state_fits(const FlexState& in, int particles, int64_t directed) const override;
  void restore(const FlexState& in) override { history_ = in.bond_history; }
  size_t memory_bytes() const override;

  // Largest stretch each stored direction has reached past s0 (0 while below).
  const std::vector<double>& history() const { return history_; }

 private:
  // f / (k s) of a bond at stretch s with history h: 1 (linear) or omega(max(h, s)).
  double secant_factor(double s, double h) const;

  SofteningStretches curve_;
  std::vector<double> history_;   // h per stored direction
  std::vector<uint8_t> linear_;   // 1: the bond touches a no-fail particle and never softens
};

}  // namespace periflex
