// The ordinary state-based law (linear peridynamic solid, LPS; constants in
// state_based_material.h, bond loops in state_based_kernel.h): any admissible Poisson ratio. Its
// pre-pass is the dilatation of every particle, which makes a particle's force depend on the
// particles two bonds away; it keeps the weighted volumes of the intact bonds per particle, and
// BondStore::coefficient holds each bond's weight w beta instead of a stiffness. Bonds break after
// the step, past s0.
#pragma once

#include <string>
#include <vector>

#include "pd/material_law.h"
#include "pd/state_based_kernel.h"

namespace periflex {

class StateBasedLaw : public MaterialLaw {
 public:
  // Checks the Poisson ratio (InputError at material.poisson_ratio); s0 from the material
  // (critical_stretch, or fracture_energy through lps_critical_stretch_from_energy).
  StateBasedLaw(const FlexBodyDef& def, double horizon, double volume, std::vector<std::string>& warnings);

  double critical_stretch() const override { return s0_; }
  // Weights w beta = k0 / (c V^2), times the LPS surface correction's bond factor.
  void set_coefficients(const LawSetup& setup, BondStore& bonds) override;
  double critical_time_step(const BondStore& bonds, const BondState& live,
                            const std::vector<double>& masses) const override;

  void add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) override;
  double strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const override;
  double damping_power(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                       double eta_over_e) const override;
  void energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                      const std::vector<double>& volumes, double* out) const override;
  bool reaches_second_neighbours() const override { return true; }

  // The strain energy does not split into bonds, but a broken bond changes the energy of its two
  // ends only: the energy released is that of the rows near s0 before minus after.
  BreakResult break_bonds(const BondStore& bonds, BondState& live, const double* pos, const uint8_t* no_fail,
                          const double* row_max) override;
  // The weighted volumes count intact bonds only.
  void bonds_cut(const BondStore& bonds, const BondState& live, std::vector<int>& particles) override;

  void save(FlexState& out) const override;
  bool state_fits(const FlexState& in, int particles, int64_t directed) const override;
  void restore(const FlexState& in) override;
  size_t memory_bytes() const override;

  const LpsFields& fields() const { return lps_; }

 private:
  double s0_;
  LpsFields lps_;
};

}  // namespace periflex
