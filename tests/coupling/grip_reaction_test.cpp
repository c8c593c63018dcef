// The multipliers of a rigid-flexible joint, straight from the acceleration solve: the resultant
// on the (massless) virtual body balances the bond forces crossing into the gripped region plus
// the region's inertia and weight, and a massless hub pinned at its centre carries no torque.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

#include "coupled_run.h"
#include "coupling/rigid_flexible_joint.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"

namespace periflex {
namespace {

TEST(GripReaction, VirtualBodyResultantBalancesCrossingBondForcesAndRegionInertia) {
  const SceneDef scene = load_scene(test::scene_path("flexible_pendulum"));
  std::unique_ptr<SystemModel> model = build_system_model(scene);
  Dynamics dynamics(*model);
  CorrectionDef no_correction;
  no_correction.method = CorrectionDef::Method::kNone;
  dynamics.set_correction(no_correction);
  dynamics.analyse(0.0);
  ASSERT_TRUE(dynamics.dropped_rows().empty());

  // the grip and its rows
  ASSERT_FALSE(model->attachments.empty());
  const RigidFlexibleJoint* grip = model->attachments.back().joint;
  const int first_row = model->attachments.back().first_row;
  ASSERT_GE(grip->body(), 0);

  // a deformed state that still satisfies the joints: free particles moved by up to 0.2 mm (a
  // strain of a few 1e-2 over the 10 mm spacing), gripped ones left where the hub carries them
  Eigen::VectorXd q = model->q0;
  std::vector<char> gripped(q.size(), 0);
  for (int c : grip->particle_coordinates()) gripped[c] = gripped[c + 1] = 1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-2e-4, 2e-4);
  for (int c = model->rigid_coordinates; c < q.size(); ++c) {
    if (!gripped[c]) q[c] += jitter(rng);
  }
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());

  Eigen::VectorXd qdd;
  Eigen::Vector3d power;
  dynamics.derivative(0.0, q, qd, qdd, power);
  const Eigen::VectorXd& lambda = dynamics.multipliers();

  // the resultant on the hub from the grip's multipliers
  Vec2 force;
  double torque = 0.0;
  grip->body_reaction(q, lambda.data() + first_row, force, torque);

  // independently: bond forces on the gripped particles (those inside the region cancel in pairs,
  // so this is what crosses into it), and the region's inertia and weight
  Eigen::VectorXd bond = Eigen::VectorXd::Zero(q.size());
  model->flex_bodies.at(0)->add_forces(q, qd, 0.0, bond);
  Vec2 crossing = Vec2::Zero(), inertia_minus_weight = Vec2::Zero();
  for (int c : grip->particle_coordinates()) {
    crossing += Vec2(bond[c], bond[c + 1]);
    inertia_minus_weight += model->mass[c] * (Vec2(qdd[c], qdd[c + 1]) - model->gravity);
  }
  ASSERT_GT(crossing.norm(), 1.0);  // the stretched bonds do pull on the grip (newtons)

  // particle equations summed over the region: sum lambda_p = sum m (a - g) - crossing, and the
  // hub receives -sum lambda_p; agreement to rounding of the sparse solve (1e-9 of the crossing force)
  const Vec2 expected = crossing - inertia_minus_weight;
  RecordProperty("crossing_x", test::sci(crossing.x()));
  RecordProperty("hub_force_x", test::sci(force.x()));
  RecordProperty("hub_torque", test::sci(torque));
  EXPECT_NEAR(force.x(), expected.x(), 1e-9 * crossing.norm());
  EXPECT_NEAR(force.y(), expected.y(), 1e-9 * crossing.norm());
  // a massless hub pinned at its centre: the pin takes no moment, so neither may the grip
  // (compared with the moment the crossing forces would make about the pin at the hub's size)
  EXPECT_NEAR(torque, 0.0, 1e-9 * crossing.norm() * 0.02);
}

}  // namespace
}  // namespace periflex
