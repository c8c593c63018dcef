// The bond loops of bond_kernel.cpp on their own: the vector strain energy against the portable one.
#include <gtest/gtest.h>

#include <random>

#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

// The AVX-512 strain energy (refined 1/|y|, a class table of |xi|) agrees with the portable sum
// to round-off, on a random field with some bonds broken (their k = 0 adds nothing).
TEST(PdKernel, VectorAndPortableStrainEnergyAgreeToRoundOff) {
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.partial_volume_correction = true;
  auto body = PdBody::build(def, 0);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 2e-7);
  Eigen::VectorXd q = test::affine_positions(*body, Eigen::Matrix2d::Identity() * 1e-4);
  for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
  // break the bonds across x = 0 (both copies) by stretching them past s0 once
  Eigen::VectorXd torn = q;
  const std::vector<double>& x = body->reference_positions();
  for (int i = 0; i < body->particle_count(); ++i) torn[2 * i] += x[2 * i] > 0.0 ? 1e-5 : 0.0;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(torn, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  ASSERT_GT(body->update_fracture(torn).bonds_broken, 0);
  set_vector_kernels(VectorKernels::kPortable);
  const double portable = body->potential_energy(q);
  set_vector_kernels(VectorKernels::kAvx512);
  const double vector = body->potential_energy(q);
  EXPECT_GT(portable, 0.0);
  EXPECT_NEAR(vector, portable, 1e-12 * portable);
}

}  // namespace
}  // namespace periflex
