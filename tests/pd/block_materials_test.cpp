// Materials by block: a body whose point file gives its blocks materials of their own. Checked
// against the closed form of a two-material strip in tension (each half strains by sigma / E_k),
// against the homogeneous bodies it is made of (bond by bond), and in fracture (each bond breaks at
// the smaller critical stretch of its ends, on every loop width).
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "pd/block_materials.h"
#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "pd_static_support.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

// A strip width x height of grid points at spacing dx, centred at the origin: block 0 where
// x < 0, block 1 where x > 0.
std::shared_ptr<ParticleCloud> two_block_strip(double width, double height, double dx, double thickness) {
  auto cloud = std::make_shared<ParticleCloud>();
  const int columns = static_cast<int>(std::lround(width / dx)), rows = static_cast<int>(std::lround(height / dx));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const double x = (i - 0.5 * (columns - 1)) * dx, y = (j - 0.5 * (rows - 1)) * dx;
      cloud->x.push_back(x);
      cloud->y.push_back(y);
      cloud->volume.push_back(dx * dx * thickness);
      cloud->no_fail.push_back(0);
      cloud->block.push_back(x < 0.0 ? 0 : 1);
    }
  cloud->source = "points strip.csv";
  return cloud;
}

// The glass strip of two_block_strip; block 1 of modulus e1 (and density rho1, critical stretch s1
// when positive), block 0 the body's glass.
FlexBodyDef two_material_strip(double width, double height, double dx, double e1, double s1 = 0.0) {
  FlexBodyDef def = test::glass_plate(width, height, dx);
  def.particles = two_block_strip(width, height, dx, def.thickness);
  BlockMaterialDef stiff;
  stiff.block = 1;
  stiff.youngs_modulus = e1;
  stiff.density = 7850.0;
  if (s1 > 0.0)
    stiff.critical_stretch = s1;
  else
    stiff.fracture_energy = 3.8;
  def.block_materials.push_back(stiff);
  return def;
}

// du_x/dx fitted by least squares (u_x = a + b x + c y) over the particles with x in [lo, hi] at
// least a horizon and a spacing from the free edges.
double axial_strain(const PdBody& body, const Eigen::VectorXd& u, double lo, double hi, double height) {
  const std::vector<double>& x = body.reference_positions();
  const double margin = body.horizon() + body.grid_spacing();
  std::vector<int> picked;
  for (int i = 0; i < body.particle_count(); ++i)
    if (x[2 * i] >= lo && x[2 * i] <= hi && std::abs(x[2 * i + 1]) < height / 2 - margin) picked.push_back(i);
  Eigen::MatrixXd a(picked.size(), 3);
  Eigen::VectorXd ux(picked.size());
  for (size_t k = 0; k < picked.size(); ++k) {
    a.row(k) << 1.0, x[2 * picked[k]], x[2 * picked[k] + 1];
    ux[k] = u[2 * picked[k]];
  }
  return a.colPivHouseholderQr().solve(ux)[1];
}

// Inside one material a bond is that material's, across the two it is the two halves in series:
// without the surface correction (which calibrates each particle against its own material) the
// stiffness of every stored direction is the homogeneous body's times 1 (block 0), E1 / E0
// (block 1) or 2 E0 E1 / (E0 + E1) / E0 (across), to the float rounding of the stored stiffness.
// Masses follow each block's density.
TEST(BlockMaterials, ABondIsItsMaterialsOrItsTwoHalvesInSeries) {
  const double dx = 1e-3, e1 = 3 * 72e9;
  FlexBodyDef def = two_material_strip(0.02, 0.01, dx, e1);
  def.surface_correction = false;
  auto mixed = PdBody::build(def, 0);
  def.block_materials.clear();
  auto glass = PdBody::build(def, 0);
  const BondStore& a = mixed->bonds();
  const BondStore& b = glass->bonds();
  ASSERT_EQ(a.neighbor, b.neighbor);
  const std::vector<double>& x = mixed->reference_positions();
  const double across = 2.0 * 1.0 * 3.0 / (1.0 + 3.0);
  int counted[3] = {0, 0, 0};
  for (int i = 0; i < mixed->particle_count(); ++i)
    for (int64_t k = a.row[i]; k < a.row[i + 1]; ++k) {
      const int j = a.neighbor[k];
      const int side_i = x[2 * i] > 0.0, side_j = x[2 * j] > 0.0;
      const int kind = side_i == side_j ? side_i : 2;
      const double ratio = kind == 0 ? 1.0 : kind == 1 ? 3.0 : across;
      ASSERT_NEAR(a.coefficient[k] / (ratio * b.coefficient[k]), 1.0, 2e-7) << "particle " << i << " bond " << k;
      ++counted[kind];
    }
  EXPECT_GT(counted[2], 100);  // bonds across the seam were checked
  EXPECT_EQ(mixed->masses()[0], glass->masses()[0]);
  EXPECT_DOUBLE_EQ(mixed->masses().back(), glass->masses().back() * 7850.0 / 2440.0);
  // the stable step comes from the stiffest and lightest particles of either block
  EXPECT_LT(mixed->critical_time_step(), glass->critical_time_step());
}

// A strip of glass (E0 = 72 GPa, x < 0) bonded to a stiffer block (E1 = 3 E0, x > 0), held at its
// left end and pulled at its right one by a uniform stress sigma: in series, each half strains by
// sigma / E_k (closed form, uniaxial stress). Fitted over each half's middle (a horizon and a
// spacing from the seam, the ends and the free edges), the two strains are within 3% of
// sigma / E_k: a homogeneous glass strip on the same grid comes to within the same (its departure
// is printed; the lattice sums of a horizon of three spacings are 1-2% off the continuum), and
// their ratio is E1 / E0 = 3 within 1% (the lattice's own error cancels in it).
TEST(BlockMaterials, ABimaterialStripInTensionStrainsEachHalfByItsOwnModulus) {
  const double width = 0.08, height = 0.016, dx = 1e-3, e1 = 3 * 72e9;
  FlexBodyDef def = two_material_strip(width, height, dx, e1);
  def.fracture = false;
  auto body = PdBody::build(def, 0);
  const double per_particle = 1.0;  // N on each particle of the last column
  const double sigma = per_particle / (dx * def.thickness);
  const Eigen::VectorXd u = test::static_tension(*body, per_particle);
  const double margin = body->horizon() + dx;
  const double left = axial_strain(*body, u, -width / 2 + margin, -margin, height);
  const double right = axial_strain(*body, u, margin, width / 2 - margin, height);
  def.block_materials.clear();
  auto glass = PdBody::build(def, 0);
  const double homogeneous = axial_strain(*glass, test::static_tension(*glass, per_particle), margin, width / 2 - margin, height);
  const double e0 = 72e9;
  std::printf("bimaterial strip: glass half %.4f, stiff half %.4f of sigma / E; ratio %.4f (3); a glass strip %.4f\n",
              left * e0 / sigma, right * e1 / sigma, left / right, homogeneous * e0 / sigma);
  EXPECT_NEAR(left * e0 / sigma, 1.0, 0.03);
  EXPECT_NEAR(right * e1 / sigma, 1.0, 0.03);
  EXPECT_NEAR(left / right / 3.0, 1.0, 0.01);
}

// Critical stretches 1e-3 (glass side) and 4e-3 (block 1): under a uniform expansion of 2e-3 every
// bond with an end in block 0 breaks (inside the glass and across the seam) and no bond inside
// block 1 does. The same bonds break in the force evaluation (portable and AVX2 loops) and in the
// break pass after a step.
TEST(BlockMaterials, EachBondBreaksAtTheSmallerCriticalStretchOfItsEnds) {
  const double dx = 1e-3;
  for (const bool in_evaluation : {true, false})
    for (const VectorKernels loops : {VectorKernels::kPortable, VectorKernels::kAvx2}) {
      set_vector_kernels(loops);
      FlexBodyDef def = two_material_strip(0.02, 0.01, dx, 72e9, 4e-3);
      def.material.fracture_energy = 0.0;
      def.material.critical_stretch = 1e-3;
      auto body = PdBody::build(def, 0);
      EXPECT_EQ(body->critical_stretch(), 1e-3);
      body->set_break_timing(in_evaluation ? PdBody::BreakTiming::kInEvaluation : PdBody::BreakTiming::kAfterStep);
      const Eigen::VectorXd q = test::affine_positions(*body, 2e-3 * Eigen::Matrix2d::Identity());
      Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
      body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
      if (in_evaluation)
        body->take_evaluation_breaks();
      else
        body->update_fracture(q);
      const BondStore& bonds = body->bonds();
      const std::vector<uint8_t>& flags = body->bond_state().broken;
      const std::vector<double>& x = body->reference_positions();
      long wrong = 0, broken = 0;
      for (int i = 0; i < body->particle_count(); ++i)
        for (int64_t k = bonds.row[i]; k < bonds.row[i + 1]; ++k) {
          const bool weak = x[2 * i] < 0.0 || x[2 * bonds.neighbor[k]] < 0.0;
          wrong += (flags[k] != 0) != weak;
          broken += flags[k] != 0;
        }
      EXPECT_EQ(wrong, 0) << (in_evaluation ? "in the evaluation" : "after the step") << ", loops " << int(loops);
      EXPECT_GT(broken, 1000);
    }
  set_vector_kernels(VectorKernels::kAvx512);
}

// The per-particle constants: a block's critical stretch from its own fracture energy and modulus,
// an unlisted block keeps the body's material.
TEST(BlockMaterials, EachParticleTakesItsBlocksConstants) {
  FlexBodyDef def = two_material_strip(0.01, 0.004, 1e-3, 200e9);
  def.block_materials.front().fracture_energy = 40.0;
  const ParticleMaterials m = particle_materials(def, static_cast<int>(def.particles->x.size()), 3e-3, 7e-4);
  ASSERT_EQ(m.modulus_ratio.size(), def.particles->x.size());
  EXPECT_EQ(m.modulus_ratio.front(), 1.0);
  EXPECT_EQ(m.density.front(), 2440.0);
  EXPECT_EQ(m.critical_stretch.front(), 7e-4);
  EXPECT_EQ(m.modulus_ratio.back(), 200e9 / 72e9);
  EXPECT_EQ(m.density.back(), 7850.0);
  EXPECT_DOUBLE_EQ(m.critical_stretch.back(), std::sqrt(4 * M_PI * 40.0 / (9 * 200e9 * 3e-3)));
  EXPECT_TRUE(particle_materials(test::glass_plate(0.01, 0.01, 1e-3), 100, 3e-3, 1e-3).empty());
}

// One law a body: the state-based law, whose constants are per body, refuses blocks of their own.
TEST(BlockMaterials, TheStateBasedLawRefusesThem) {
  FlexBodyDef def = two_material_strip(0.01, 0.004, 1e-3, 200e9);
  def.material.model = PdMaterialDef::Model::kStateBased;
  def.material.poisson_ratio = 0.25;
  try {
    PdBody::build(def, 0);
    FAIL() << "built";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bond-based"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace periflex
