// The material-law interface (src/pd/material_law.h): the catalogue picks the law a material's
// model names, and every law keeps the same contract with the body, checked once and run for each
// law: forces are minus the gradient of its strain energy, its energy densities add up to that
// energy, and a body cut and restored is the body it was.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pd/bilinear_softening_law.h"
#include "pd/bond_based_law.h"
#include "pd/material_law.h"
#include "pd/pd_body.h"
#include "pd/pd_material.h"
#include "pd/state_based_law.h"
#include "pd/state_based_material.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

FlexBodyDef plate_of(PdMaterialDef::Model model) {
  FlexBodyDef def = test::glass_plate(0.012, 0.008, 1e-3);
  def.material.model = model;
  if (model == PdMaterialDef::Model::kStateBased) def.material.poisson_ratio = 0.22;
  if (model == PdMaterialDef::Model::kBilinearSoftening) def.material.softening_ratio = 6.0;
  return def;
}

std::string model_name(PdMaterialDef::Model model) {
  switch (model) {
    case PdMaterialDef::Model::kBondBased: return "bond_based";
    case PdMaterialDef::Model::kStateBased: return "state_based";
    case PdMaterialDef::Model::kBilinearSoftening: return "bilinear_softening";
  }
  return "";
}

TEST(MaterialLawCatalogue, BuildsTheLawTheModelNamesWithItsCriticalStretch) {
  std::vector<std::string> warnings;
  const double delta = 3e-3, g0 = 3.8, e = 72e9;
  const FlexBodyDef bond = plate_of(PdMaterialDef::Model::kBondBased);
  const auto bond_law = make_material_law(bond, delta, 1e-9, warnings);
  ASSERT_NE(dynamic_cast<BondBasedLaw*>(bond_law.get()), nullptr);
  EXPECT_DOUBLE_EQ(bond_law->critical_stretch(),
                   critical_stretch_from_energy(g0, e, delta, false, FlexBodyDef::Influence::kConstant));

  const FlexBodyDef state = plate_of(PdMaterialDef::Model::kStateBased);
  const auto state_law = make_material_law(state, delta, 1e-9, warnings);
  ASSERT_NE(dynamic_cast<StateBasedLaw*>(state_law.get()), nullptr);
  EXPECT_DOUBLE_EQ(state_law->critical_stretch(),
                   lps_critical_stretch_from_energy(g0, e, 0.22, delta, false, FlexBodyDef::Influence::kConstant));

  const FlexBodyDef soft = plate_of(PdMaterialDef::Model::kBilinearSoftening);
  const auto soft_law = make_material_law(soft, delta, 1e-9, warnings);
  const auto* softening = dynamic_cast<BilinearSofteningLaw*>(soft_law.get());
  ASSERT_NE(softening, nullptr);
  const double sc = critical_stretch_from_energy(g0, e, delta, false, FlexBodyDef::Influence::kConstant);
  EXPECT_NEAR(softening->critical_stretch(), sc / std::sqrt(6.0), 1e-15);
  EXPECT_NEAR(softening->final_stretch(), sc * std::sqrt(6.0), 1e-15);
  EXPECT_TRUE(warnings.empty());
}

TEST(MaterialLawCatalogue, WarnsWhenFractureIsOnWithoutACriterion) {
  FlexBodyDef def = plate_of(PdMaterialDef::Model::kBondBased);
  def.material.fracture_energy = 0.0;
  std::vector<std::string> warnings;
  const auto law = make_material_law(def, 3e-3, 1e-9, warnings);
  EXPECT_TRUE(std::isinf(law->critical_stretch()));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("bonds will not break"), std::string::npos);
}

class EveryLaw : public ::testing::TestWithParam<PdMaterialDef::Model> {};

// a plate stretched unevenly (a quadratic field, so no two rows see the same strain) with the
// softening law's bonds well past s0 where the strain is largest
Eigen::VectorXd uneven(const PdBody& body, double amount) {
  const std::vector<double>& x = body.reference_positions();
  Eigen::VectorXd q(x.size());
  for (size_t i = 0; i < x.size(); i += 2) {
    const double px = x[i], py = x[i + 1];
    q[static_cast<Eigen::Index>(i)] = px + amount * (px + 40.0 * px * px + 10.0 * px * py);
    q[static_cast<Eigen::Index>(i + 1)] = py - 0.3 * amount * py + amount * 30.0 * px * py;
  }
  return q;
}

TEST_P(EveryLaw, ForcesAreMinusTheGradientOfTheStrainEnergy) {
  test::SerialScope serial;
  FlexBodyDef def = plate_of(GetParam());
  def.fracture = false;  // the history stays as it is: the energy is that of the force's curve
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = uneven(*body, 2e-4);
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, qd, 0.0, g);
  // central differences of the energy at a few coordinates; h small against the strain, the error
  // O(h^2) far below 1e-5 of the force scale
  const double h = 1e-11;
  double scale = 0.0;
  for (Eigen::Index c = 0; c < g.size(); ++c) scale = std::max(scale, std::abs(g[c]));
  for (const Eigen::Index c : {Eigen::Index{10}, Eigen::Index{57}, g.size() / 2 + 3, g.size() - 8}) {
    Eigen::VectorXd plus = q, minus = q;
    plus[c] += h;
    minus[c] -= h;
    const double derivative = (body->potential_energy(plus) - body->potential_energy(minus)) / (2.0 * h);
    EXPECT_NEAR(g[c], -derivative, 1e-5 * scale) << "coordinate " << c;
  }
}

TEST_P(EveryLaw, EnergyDensitiesAddUpToTheStrainEnergy) {
  test::SerialScope serial;
  auto body = PdBody::build(plate_of(GetParam()), 0);
  const Eigen::VectorXd q = uneven(*body, 2e-4);
  std::vector<double> density;
  body->strain_energy_density(q, density);
  double sum = 0.0;
  for (int i = 0; i < body->particle_count(); ++i) sum += density[i] * body->volumes()[i];
  const double energy = body->potential_energy(q);
  EXPECT_GT(energy, 0.0);
  EXPECT_NEAR(sum, energy, 1e-10 * energy);
}

TEST_P(EveryLaw, ARestoredStateGivesTheSameForcesAndEnergy) {
  test::SerialScope serial;
  auto body = PdBody::build(plate_of(GetParam()), 0);
  body->set_break_timing(PdBody::BreakTiming::kAfterStep);  // evaluations hold every bond
  const Eigen::VectorXd q = uneven(*body, 2e-4);
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());
  auto forces = [&]() {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
    body->add_forces(q, qd, 0.0, g);
    return g;
  };
  FlexState saved;
  body->save_state(saved);
  const Eigen::VectorXd g_before = forces();
  const double e_before = body->potential_energy(q);
  // the step's break pass (the softening law's history grows), then a cut across the plate
  body->update_fracture(q);
  body->cut_bonds(q, {}, Vec2(0.0005, -0.01), Vec2(0.0005, 0.01));
  ASSERT_GT(body->broken_bond_count(), 0);
  body->restore_state(saved);
  EXPECT_EQ(body->broken_bond_count(), 0);
  EXPECT_EQ(body->potential_energy(q), e_before);
  const Eigen::VectorXd g_after = forces();
  for (Eigen::Index c = 0; c < q.size(); ++c) ASSERT_EQ(g_after[c], g_before[c]) << "coordinate " << c;
}

INSTANTIATE_TEST_SUITE_P(Laws, EveryLaw,
                         ::testing::Values(PdMaterialDef::Model::kBondBased, PdMaterialDef::Model::kStateBased,
                                           PdMaterialDef::Model::kBilinearSoftening),
                         [](const ::testing::TestParamInfo<PdMaterialDef::Model>& law) {
                           return model_name(law.param);
                         });

}  // namespace
}  // namespace periflex
