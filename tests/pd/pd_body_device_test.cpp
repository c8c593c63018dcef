// The kernel seam (pd/bond_force_device.h, pd_body_device.cpp) without a GPU: a device that runs
// the CPU's own loops must leave a body's forces and breaks bit for bit as the CPU path has them,
// be uploaded once, and be told of every change the host makes to the bonds outside its
// evaluations. Only the bond-based law may have a device; none is installed by default.
#include <gtest/gtest.h>

#include <stdexcept>

#include "pd/bond_force_device.h"
#include "pd/bond_kernel.h"
#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

using test::glass_plate;

// A device that evaluates with the CPU loops and counts what the body asks of it.
struct CountingDevice : BondForceDevice {
  int uploads = 0, changes = 0, evaluations = 0;
  const uint8_t* no_fail = nullptr;
  std::string name = "CPU loops behind the seam";

  const std::string& description() const override { return name; }
  void upload(const BondStore&, const BondState&, const uint8_t* flags, const double*) override {
    ++uploads;
    no_fail = flags;
  }
  void bonds_changed() override { ++changes; }
  void add_forces(const BondStore& bonds, BondState& live, const DeviceEvaluation& e) override {
    ++evaluations;
    const double* vel = e.eta_over_e > 0.0 ? e.vel : nullptr;
    if (e.breaking) {
      BreakingEvaluation breaking;
      breaking.s0 = e.s0;
      breaking.no_fail = no_fail;
      breaking.row_broke = e.row_broke;
      add_bond_forces_breaking(bonds, live, e.pos, e.vel, e.eta_over_e, breaking, e.force);
    } else if (vel) {
      add_damped_bond_forces(bonds, live, e.pos, vel, e.eta_over_e, e.force, e.row_max);
    } else {
      add_bond_forces(bonds, live, e.pos, e.force, e.row_max);
    }
  }
};

// The plate's right half stretched along x to 3 s0, the left half not at all: bonds across the
// middle and in the right half break.
Eigen::VectorXd half_stretched(const PdBody& body) {
  const std::vector<double>& x = body.reference_positions();
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  const double strain = 3.0 * body.critical_stretch();
  for (int i = 0; i < body.particle_count(); ++i)
    if (x[2 * i] > 0.0) q[2 * i] += strain * x[2 * i];
  return q;
}

struct Pair {
  std::unique_ptr<PdBody> cpu, seam;
  CountingDevice* device = nullptr;
};
Pair make_pair(const FlexBodyDef& def) {
  Pair p{PdBody::build(def, 0), PdBody::build(def, 0)};
  auto device = std::make_unique<CountingDevice>();
  p.device = device.get();
  p.seam->use_bond_force_device(std::move(device));
  return p;
}

void expect_same_evaluation(Pair& p, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(q.size()), b = Eigen::VectorXd::Zero(q.size());
  p.cpu->add_forces(q, qd, 0.0, a);
  p.seam->add_forces(q, qd, 0.0, b);
  EXPECT_TRUE(a == b);
  EXPECT_EQ(p.seam->broken_bond_count(), p.cpu->broken_bond_count());
  EXPECT_TRUE(p.seam->bond_state().broken == p.cpu->bond_state().broken);
  const FractureUpdate x = p.cpu->take_evaluation_breaks(), y = p.seam->take_evaluation_breaks();
  EXPECT_EQ(y.bonds_broken, x.bonds_broken);
  EXPECT_EQ(y.energy_released, x.energy_released);
}

TEST(PdBodyDevice, BreaksInTheEvaluationAsTheCpuPathDoes) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 5e-4);
  Pair p = make_pair(def);
  EXPECT_EQ(p.device->uploads, 1);
  const Eigen::VectorXd q = half_stretched(*p.cpu);
  Eigen::VectorXd qd = Eigen::VectorXd::Constant(q.size(), 0.3);
  for (int i = 0; i < qd.size(); i += 3) qd[i] = -0.7;
  p.cpu->set_bond_damping(1e-6 * def.material.youngs_modulus);
  p.seam->set_bond_damping(1e-6 * def.material.youngs_modulus);
  expect_same_evaluation(p, q, qd);
  EXPECT_GT(p.cpu->broken_bond_count(), 0);
  EXPECT_EQ(p.device->evaluations, 1);
  // breaks made in the device's own evaluation are not a change it must be told of
  EXPECT_EQ(p.device->changes, 0);
}

TEST(PdBodyDevice, IsToldOfEveryChangeToTheBondsOutsideItsEvaluations) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 5e-4);
  Pair p = make_pair(def);
  FlexState before;
  p.seam->save_state(before);
  // the break pass after the step, from the device's row maxima
  p.cpu->set_break_timing(PdBody::BreakTiming::kAfterStep);
  p.seam->set_break_timing(PdBody::BreakTiming::kAfterStep);
  const Eigen::VectorXd q = half_stretched(*p.cpu), qd = Eigen::VectorXd::Zero(q.size());
  expect_same_evaluation(p, q, qd);
  const FractureUpdate x = p.cpu->update_fracture(q), y = p.seam->update_fracture(q);
  EXPECT_GT(x.bonds_broken, 0);
  EXPECT_EQ(y.bonds_broken, x.bonds_broken);
  EXPECT_EQ(y.energy_released, x.energy_released);
  EXPECT_EQ(p.device->changes, 1);
  // the knife
  const Eigen::VectorXd rest = Eigen::Map<const Eigen::VectorXd>(p.seam->reference_positions().data(), q.size());
  EXPECT_GT(p.seam->cut_bonds(rest, {}, Vec2(-0.004, -0.006), Vec2(-0.004, 0.006)).bonds_broken, 0);
  EXPECT_EQ(p.device->changes, 2);
  // a restored state heals bonds
  p.seam->restore_state(before);
  EXPECT_EQ(p.device->changes, 3);
  EXPECT_EQ(p.device->uploads, 1);
}

TEST(PdBodyDevice, OnlyTheBondBasedLawRunsOnADevice) {
  FlexBodyDef def = glass_plate(0.01, 0.01, 1e-3);
  def.material.model = PdMaterialDef::Model::kStateBased;
  def.material.poisson_ratio = 0.25;
  auto body = PdBody::build(def, 0);
  try {
    body->use_bond_force_device(std::make_unique<CountingDevice>());
    FAIL() << "a state-based body took a device";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bond_based"), std::string::npos) << e.what();
  }
  EXPECT_EQ(body->bond_force_device(), nullptr);
}

TEST(PdBodyDevice, NoDeviceIsInstalledByDefault) {
  EXPECT_FALSE(bond_force_device_installed());
  EXPECT_THROW(make_bond_force_device(), std::runtime_error);
  install_bond_force_device([](DevicePrecision) { return std::make_unique<CountingDevice>(); });
  EXPECT_TRUE(bond_force_device_installed());
  EXPECT_NE(make_bond_force_device(), nullptr);
  install_bond_force_device({});
  EXPECT_FALSE(bond_force_device_installed());
}

}  // namespace
}  // namespace periflex
