// The bond-based law (prototype microelastic brittle, Silling 2000): each bond a linear spring
// k s between its two particles, broken for good past the critical stretch s0. Poisson's ratio is
// fixed by the model (1/3 plane stress, 1/4 plane strain). The bond loops are in bond_kernel.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "pd/material_law.h"

namespace periflex {

class BondBasedLaw : public MaterialLaw {
 public:
  // s0 from the material (critical_stretch, or fracture_energy through critical_stretch_from_energy);
  // a stated Poisson ratio the model cannot represent is a warning.
  BondBasedLaw(const FlexBodyDef& def, double horizon, std::vector<std::string>& warnings);

  double critical_stretch() const override { return s0_; }
  // k = k0 times the surface correction's factor (set_bond_stiffness).
  void set_coefficients(const LawSetup& setup, BondStore& bonds) override;
  double critical_time_step(const BondStore& bonds, const BondState& live,
                            const std::vector<double>& masses) const override;

  void add_forces(const BondStore& bonds, const BondState& live, const LawEvaluation& e) override;
  bool breaks_in_evaluation() const override { return true; }
  long add_forces_breaking(const BondStore& bonds, BondState& live, const LawEvaluation& e, const uint8_t* no_fail,
                           std::vector<uint8_t>& row_broke, double half_kick, double& energy) override;
  double strain_energy(const BondStore& bonds, const BondState& live, const double* pos) const override;
  double damping_power(const BondStore& bonds, const BondState& live, const double* pos, const double* vel,
                       double eta_over_e) const override;
  void energy_density(const BondStore& bonds, const BondState& live, const double* pos,
                      const std::vector<double>& volumes, double* out) const override;

  BreakResult break_bonds(const BondStore& bonds, BondState& live, const double* pos, const uint8_t* no_fail,
                          const double* row_max) override;

 private:
  double s0_;
};

// Final bond stiffness k = k0 G, G the energy-method surface correction (identity when the body
// turns it off). Shared by the laws whose bonds are springs.
void set_bond_stiffness(const LawSetup& setup, BondStore& bonds);

// Silling & Askari (2005): sqrt(2 m_i / sum_b k_b / |xi_b|) over the bonds intact in `live`, min over
// particles.
double spring_critical_time_step(const BondStore& bonds, const BondState& live, const std::vector<double>& masses);

}  // namespace periflex
