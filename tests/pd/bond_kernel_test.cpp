// The bond loops of bond_kernel.cpp: the vector loops against the portable ones, forces bit for
// bit across thread counts, the damping power, forces as the gradient of the energy, and the
// same bonds broken with or without the force passes' stretch maxima.
#include <gtest/gtest.h>

#include <random>

#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "pd_test_support.h"
#include <omp.h>
#include <memory>
#include "pd/pd_material.h"

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

namespace periflex {
namespace {

using test::affine_positions;
using test::glass_plate;
using test::uniaxial;

TEST(PdDeterminism, ForcesAreBitIdenticalAcrossThreadCounts) {
  // each particle gathers its own bonds in a fixed order, so the thread count cannot change a bit;
  // the energy is summed in fixed ranges added in order: the same bits too
  FlexBodyDef def = glass_plate(0.05, 0.03, 5e-4);
  def.bond_damping = 1e3;
  auto body = PdBody::build(def, 0);
  // the same state is evaluated three times: nothing may break in between
  body->set_break_timing(PdBody::BreakTiming::kAfterStep);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-6);
  Eigen::VectorXd q = affine_positions(*body, uniaxial(1e-4)), qd(q.size());
  for (int k = 0; k < q.size(); ++k) {
    q[k] += noise(rng);
    qd[k] = noise(rng) * 1e3;
  }
  const int saved = omp_get_max_threads();
  std::vector<Eigen::VectorXd> forces;
  std::vector<double> energies;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
    body->add_forces(q, qd, 0.0, g);
    forces.push_back(g);
    energies.push_back(body->potential_energy(q));
  }
  omp_set_num_threads(saved);
  for (size_t k = 1; k < forces.size(); ++k) {
    EXPECT_EQ(forces[k], forces[0]);
    EXPECT_EQ(energies[k], energies[0]) << "thread counts 1 and " << k + 1;
  }
}

// A plate in a random state near the reference, for kernel comparisons.
struct Perturbed {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd;
};

Perturbed perturbed_plate(double bond_damping, double global_damping) {
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.bond_damping = bond_damping;
  def.global_damping = global_damping;
  Perturbed p;
  p.body = PdBody::build(def, 0);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1e-6);
  p.q = test::affine_positions(*p.body, Eigen::Matrix2d::Identity() * 1e-4);
  p.qd.resize(p.q.size());
  for (int k = 0; k < p.q.size(); ++k) {
    p.q[k] += noise(rng);
    p.qd[k] = noise(rng) * 1e3;
  }
  return p;
}

TEST(PdKernel, VectorAndPortableLoopsAgreeToRoundOff) {
  // same formula, different summation order (and, in the AVX-512 loops, 1/|y| refined from an
  // estimate): 1e-12 of the largest force component. Each width the CPU lacks runs the next
  // narrower loop, so the comparison then holds trivially.
  for (VectorKernels width : {VectorKernels::kAvx2, VectorKernels::kAvx512}) {
    for (double eta : {0.0, 50.0}) {
      Perturbed p = perturbed_plate(eta, 0.0);
      Eigen::VectorXd g_vec = Eigen::VectorXd::Zero(p.q.size()), g_port = g_vec;
      set_vector_kernels(width);
      p.body->add_forces(p.q, p.qd, 0.0, g_vec);
      set_vector_kernels(VectorKernels::kPortable);
      p.body->add_forces(p.q, p.qd, 0.0, g_port);
      set_vector_kernels(VectorKernels::kAvx512);
      EXPECT_LT((g_vec - g_port).cwiseAbs().maxCoeff(), 1e-12 * g_port.cwiseAbs().maxCoeff())
          << "width " << static_cast<int>(width) << ", eta " << eta;
    }
  }
}

TEST(PdKernel, RowMaximaOfTheForceLoopsMatchTheExactStretch) {
  // the force loops' by-product row maxima let the fracture pass skip rows; they must agree
  // with the exact stretch (max_bond_stretch at the same positions) to far below any s0
  for (VectorKernels width : {VectorKernels::kPortable, VectorKernels::kAvx2, VectorKernels::kAvx512}) {
    Perturbed p = perturbed_plate(0.0, 0.0);
    set_vector_kernels(width);
    std::vector<double> most(p.body->particle_count());
    Eigen::VectorXd g = Eigen::VectorXd::Zero(p.q.size());
    add_bond_forces(p.body->bonds(), p.body->bond_state(), p.q.data(), g.data(), most.data());
    set_vector_kernels(VectorKernels::kAvx512);
    const BondStore& b = p.body->bonds();
    const std::vector<float>& stiffness = p.body->bond_state().stiffness;
    double worst = 0.0;
    for (int i = 0; i < b.particle_count(); ++i) {
      double exact = -1.0;
      for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
        const int j = b.neighbor[k];
        const double dx = p.q[2 * j] - p.q[2 * i], dy = p.q[2 * j + 1] - p.q[2 * i + 1];
        if (stiffness[k] > 0.0f) exact = std::max(exact, std::sqrt(dx * dx + dy * dy) * b.inv_length(k) - 1.0);
      }
      worst = std::max(worst, std::abs(most[i] - exact));
    }
    // a few units in the last place of a stretch near 1e-4; far below the fracture pass's slack
    EXPECT_LT(worst, 1e-13) << static_cast<int>(width);
  }
}

TEST(PdDamping, DissipationPowerIsMinusTheDampingForcesPower) {
  // the power the damping forces do on the particles (forces with damping minus forces
  // without, dotted with qd) must be the negative of the reported dissipation; 1e-9 relative:
  // round-off in the difference of two large force vectors
  Perturbed p = perturbed_plate(50.0, 300.0);
  Eigen::VectorXd g_damped = Eigen::VectorXd::Zero(p.q.size()), g_plain = g_damped;
  p.body->add_forces(p.q, p.qd, 0.0, g_damped);
  const double dissipated = p.body->dissipation_power(p.q, p.qd);
  p.body->set_bond_damping(0.0);
  p.body->set_global_damping(0.0);
  p.body->add_forces(p.q, p.qd, 0.0, g_plain);
  EXPECT_EQ(p.body->dissipation_power(p.q, p.qd), 0.0);
  const double power = (g_damped - g_plain).dot(p.qd);
  EXPECT_GT(dissipated, 0.0);
  EXPECT_NEAR(-power / dissipated, 1.0, 1e-9);
}

TEST(PdElasticity, BondForcesAreTheGradientOfTheStrainEnergy) {
  // central differences of potential_energy against add_forces on a few coordinates;
  // 1e-5 relative: the O(h^2) error of the difference
  Perturbed p = perturbed_plate(0.0, 0.0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(p.q.size());
  p.body->add_forces(p.q, Eigen::VectorXd::Zero(p.q.size()), 0.0, g);
  const double h = 1e-9;
  for (int k : {0, 1, 501, 1200, static_cast<int>(p.q.size()) - 1}) {
    Eigen::VectorXd qp = p.q, qm = p.q;
    qp[k] += h;
    qm[k] -= h;
    const double numeric = -(p.body->potential_energy(qp) - p.body->potential_energy(qm)) / (2 * h);
    EXPECT_NEAR(numeric / g[k], 1.0, 1e-5) << k;
  }
}

TEST(PdDamage, BreaksTheSameBondsWithOrWithoutTheForcePassesStretchMaxima) {
  // update_fracture reuses the stretch maxima of a force evaluation at the same positions;
  // the bonds it breaks must be exactly those a fresh stretch pass finds
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.material.critical_stretch = 1e-4;
  auto with_forces = PdBody::build(def, 0), alone = PdBody::build(def, 0);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 4e-8);
  Eigen::VectorXd q = test::affine_positions(*alone, Eigen::Matrix2d::Identity() * 9e-5);
  for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  with_forces->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  const FractureUpdate a = with_forces->update_fracture(q), b = alone->update_fracture(q);
  EXPECT_GT(a.bonds_broken, 0);
  EXPECT_LT(a.bonds_broken, alone->bond_count());
  EXPECT_EQ(a.bonds_broken, b.bonds_broken);
  EXPECT_EQ(a.energy_released, b.energy_released);
  EXPECT_EQ(with_forces->bond_state().broken, alone->bond_state().broken);
}

}  // namespace
}  // namespace periflex
