// The mouse's grip on a flexible body (solve/mouse_grip.h): its anchor walks to the pointer at
// the capped speed in simulated time, whatever the step; its pull stays at its limit; and on the
// notched plate a drag across the notch tears the ligament from the notch tip instead of blowing
// the plate to dust.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/scene_loader.h"
#include "solve/mouse_grip.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

// A free 10 mm x 10 mm elastic plate (E = 1 GPa, rho = 1000 kg/m^3: wave speed 1000 m/s), at
// rest, without fracture, optionally clamped along its left edge.
SceneDef plate(double dt_fraction, bool clamped) {
  SceneDef scene = test::empty_scene("verlet", 1e-9, CorrectionDef::Method::kNone);
  scene.gravity = Vec2::Zero();
  scene.solver.end_time = 1.0;
  FlexBodyDef body;
  body.name = "plate";
  body.shape.kind = ShapeDef::Kind::kBox;
  body.shape.width = body.shape.height = 0.01;
  body.grid_spacing = 1e-3;
  body.thickness = 1e-3;
  body.material.youngs_modulus = 1e9;
  body.material.density = 1000.0;
  body.material.critical_stretch = 0.01;
  body.fracture = false;
  if (clamped) {
    RegionLoadDef clamp;
    clamp.name = "clamp";
    clamp.kind = RegionLoadDef::Kind::kPrescribedDisplacement;
    clamp.region.kind = ShapeDef::Kind::kBox;
    clamp.region.center = Vec2(-0.0045, 0.0);
    clamp.region.width = 0.002;
    clamp.region.height = 0.012;
    clamp.fx = TimeFunction::constant(0.0);
    clamp.fy = TimeFunction::constant(0.0);
    body.loads.push_back(clamp);
  }
  scene.flex_bodies.push_back(body);
  Simulation probe(scene);
  scene.solver.dt = dt_fraction * probe.info().critical_time_step;
  return scene;
}

// The particle nearest `at`.
int nearest(const Snapshot& snap, const Vec2& at) {
  int best = 0;
  for (int i = 0; i < static_cast<int>(snap.px.size()); ++i) {
    if ((Vec2(snap.px[i], snap.py[i]) - at).norm() < (Vec2(snap.px[best], snap.py[best]) - at).norm()) best = i;
  }
  return best;
}

TEST(MouseGrip, LimitsFollowTheWaveSpeedAndThePatchStrength) {
  const GripLimits soft = grip_limits(3.2e9, 1190.0, 6.6e-3, 3e-3, 5e-3, false);
  EXPECT_NEAR(soft.max_speed, 1e-3 * std::sqrt(3.2e9 / 1190.0), 1e-12);
  EXPECT_NEAR(soft.max_force, 3.2e9 * 6.6e-3 * 2.0 * kPi * 3e-3 * 5e-3, 1e-9);
  const GripLimits hard = grip_limits(3.2e9, 1190.0, 6.6e-3, 3e-3, 5e-3, true);
  EXPECT_NEAR(hard.max_speed, kHardGripFactor * soft.max_speed, 1e-12);
  EXPECT_NEAR(hard.max_force, kHardGripFactor * soft.max_force, 1e-9);
}

// The anchor walks from the grabbed particle to a target 2 mm away at 1e-3 of the wave speed
// (1 m/s here) in simulated time: at every step it lies min(v t, 2 mm) along the way, with steps
// of 0.55 and then 0.8 of the critical one (neither divides the walk's 2 ms), and it arrives at
// the first step at or after 2 ms, not a step later.
TEST(MouseGrip, AnchorWalksAtTheCappedSpeedWhateverTheStep) {
  for (double fraction : {0.55, 0.8}) {
    SCOPED_TRACE(fraction);
    Simulation sim(plate(fraction, false));
    sim.initialize();
    Snapshot snap;
    sim.fill_snapshot(snap);
    const int grabbed = nearest(snap, Vec2::Zero());
    const Vec2 start(snap.px[grabbed], snap.py[grabbed]);
    const Vec2 target = start + Vec2(1.6e-3, 1.2e-3);  // 2 mm away
    MouseSpring grab;
    grab.particle = grabbed;
    grab.target = target;
    ASSERT_GT(sim.set_mouse_spring(grab), 0.0);
    sim.fill_snapshot(snap);
    ASSERT_TRUE(snap.mouse.held);
    // the walk starts at the grabbed particle (in double precision: the snapshot's px are floats)
    ASSERT_LT((snap.mouse.anchor - start).norm(), 1e-9);
    const Vec2 from = snap.mouse.anchor;
    const double v = snap.mouse.max_speed;
    EXPECT_NEAR(v, 1e-3 * std::sqrt(1e9 / 1000.0), 1e-12);
    const double t0 = sim.time(), walk = (target - from).norm() / v;
    ASSERT_GT(std::fmod(walk, sim.scene().solver.dt), 1e-3 * sim.scene().solver.dt);  // no whole number of steps
    bool arrived = false;
    while (!arrived) {
      sim.step();
      sim.fill_snapshot(snap);
      const double along = (snap.mouse.anchor - from).norm(), t = sim.time() - t0;
      // (the free plate follows closely: the pull stays far under its limit, the anchor never waits)
      ASSERT_LT(snap.mouse.force, snap.mouse.max_force);
      EXPECT_NEAR(along, std::min(v * t, (target - from).norm()), 1e-9 * 2e-3) << "t = " << t;
      EXPECT_NEAR((snap.mouse.anchor - from).normalized().dot((target - from).normalized()), 1.0, 1e-12);
      arrived = (snap.mouse.anchor - target).norm() < 1e-15;
      if (arrived) {
        EXPECT_LT(t - walk, sim.scene().solver.dt * (1 + 1e-9));
      }
      ASSERT_LT(t, 1.1 * walk) << "the anchor never arrived";
    }
  }
}

// Shift pressed during a drag (the same grab again, hard): the anchor's speed and the pull's
// limit ten times higher from then on; let go, back to the gentle grip. The anchor keeps its
// place when the grip changes (no jump).
TEST(MouseGrip, HardGripDuringADragIsTenTimesFasterAndStronger) {
  Simulation sim(plate(0.6, false));
  sim.initialize();
  Snapshot snap;
  sim.fill_snapshot(snap);
  MouseSpring grab;
  grab.particle = nearest(snap, Vec2::Zero());
  grab.target = Vec2(0.004, 0.0);
  sim.set_mouse_spring(grab);
  sim.fill_snapshot(snap);
  const double speed = snap.mouse.max_speed, force = snap.mouse.max_force;
  for (int k = 0; k < 50; ++k) sim.step();
  sim.fill_snapshot(snap);
  const Vec2 before = snap.mouse.anchor;
  grab.hard = true;
  sim.set_mouse_spring(grab);
  sim.fill_snapshot(snap);
  EXPECT_DOUBLE_EQ(snap.mouse.max_speed, kHardGripFactor * speed);
  EXPECT_DOUBLE_EQ(snap.mouse.max_force, kHardGripFactor * force);
  EXPECT_LT((snap.mouse.anchor - before).norm(), 1e-15);
  grab.hard = false;
  sim.set_mouse_spring(grab);
  sim.fill_snapshot(snap);
  EXPECT_DOUBLE_EQ(snap.mouse.max_speed, speed);
  EXPECT_DOUBLE_EQ(snap.mouse.max_force, force);
}

// A plate clamped on its left edge, its right edge pulled 5 mm to the right: the anchor waits at
// the pull's limit (it stops short of the pointer), and the pull never exceeds the limit by more
// than one step of the anchor's walk (stiffness * v * dt).
TEST(MouseGrip, PullStaysAtItsLimit) {
  Simulation sim(plate(0.6, true));
  sim.initialize();
  Snapshot snap;
  sim.fill_snapshot(snap);
  MouseSpring grab;
  grab.particle = nearest(snap, Vec2(0.0045, 0.0));
  grab.target = Vec2(0.0095, 0.0);
  const double stiffness = sim.set_mouse_spring(grab);
  sim.fill_snapshot(snap);
  const double limit = snap.mouse.max_force, v = snap.mouse.max_speed, dt = sim.scene().solver.dt;
  ASSERT_GT(limit, 0.0);
  double largest = 0.0;
  // 5 ms: time enough for the anchor to walk the whole 5 mm had nothing held it back
  const long steps = static_cast<long>(5e-3 / dt) + 10;
  for (long k = 0; k < steps; ++k) {
    sim.step();
    sim.fill_snapshot(snap);
    largest = std::max(largest, snap.mouse.force);
  }
  EXPECT_LE(largest, limit + stiffness * v * dt * 1.01);
  EXPECT_GT(largest, 0.5 * limit) << "the clamped plate never pulled back";
  EXPECT_GT((snap.mouse.anchor - snap.mouse.target).norm(), 1e-3) << "the anchor reached the pointer";
}

// The shipped notched plate with its grips held still (drivers at rate 0, so any crack is the
// drag's): a patch just right of the notch's mouth pulled 10 mm to the right, as a hand drags in
// the window. Within 0.5 ms the notch opens and a crack runs up from its tip, and no more than 3 %
// of the particles lose over half their bonds (before the grip was limited, 0.3 ms of such a drag
// left damage across the whole plate).
TEST(MouseGrip, DragAcrossTheNotchTearsTheLigamentWithoutDust) {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                                    {"driver.left_turn.function.rate=0", "driver.right_turn.function.rate=0"});
  Simulation sim(scene);
  sim.initialize();
  Snapshot snap;
  sim.fill_snapshot(snap);
  MouseSpring grab;
  grab.particle = nearest(snap, Vec2(0.004, -0.017));
  grab.target = Vec2(0.014, -0.017);
  ASSERT_GT(sim.set_mouse_spring(grab), 0.0);
  // where the first damage shows (over a quarter, checked every 10 us): at the notch tip
  const auto& geometry = *snap.geometry;
  bool first = true;
  while (first && sim.time() < 0.5e-3) {
    sim.advance_to(sim.time() + 1e-5);
    sim.fill_snapshot(snap);
    for (size_t i = 0; i < snap.damage.size(); ++i) {
      if (snap.damage[i] <= 0.25f) continue;
      first = false;
      const Vec2 at(geometry.reference_x[i], geometry.reference_y[i]);
      EXPECT_LT((at - Vec2(0.0, -0.012)).norm(), 3e-3) << "first damage at (" << at.x() << ", " << at.y()
                                                       << "), t = " << sim.time();
    }
  }
  EXPECT_FALSE(first) << "no damage within 0.5 ms";
  sim.advance_to(0.5e-3);
  sim.fill_snapshot(snap);
  long dust = 0;
  double crack_top = -1.0;
  for (size_t i = 0; i < snap.damage.size(); ++i) {
    if (snap.damage[i] > 0.5f) ++dust;
    // a crack from the notch tip (x = 0, y = -0.012): damaged particles above it near x = 0
    if (snap.damage[i] > 0.25f && std::abs(geometry.reference_x[i]) < 3e-3)
      crack_top = std::max(crack_top, static_cast<double>(geometry.reference_y[i]));
  }
  const double share = static_cast<double>(dust) / static_cast<double>(snap.damage.size());
  std::printf("dust %ld of %zu (%.4f), crack top %.4g m, pull %.4g N of %.4g N, broken %ld\n", dust,
              snap.damage.size(), share, crack_top, snap.mouse.force, snap.mouse.max_force, snap.broken_bonds);
  EXPECT_LT(share, 0.03);
  EXPECT_GT(crack_top, -0.012 + 3e-3) << "no crack ran up from the notch tip";
}

}  // namespace
}  // namespace periflex
