// Rigid limit of the coupled scenes: with a stiff peridynamic link the flexible mechanisms
// must move like their rigid counterparts, whose motion is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "coupled_run.h"
#include "core/vec2.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"
#include "study/elliptic.h"

namespace periflex {
namespace {

const BodyDef& body_named(const SceneDef& scene, const std::string& name) {
  for (const BodyDef& b : scene.bodies) {
    if (b.name == name) return b;
  }
  throw std::runtime_error("no body " + name);
}

const JointDef& joint_named(const SceneDef& scene, const std::string& name) {
  for (const JointDef& j : scene.joints) {
    if (j.name == name) return j;
  }
  throw std::runtime_error("no joint " + name);
}

TEST(RigidLimit, StiffFlexiblePendulumSwingsWithTheCompoundPendulumPeriod) {
  // a beam 10x stiffer than the scene's: first bending mode near 80 Hz against a 0.73 Hz swing
  SceneDef scene = load_scene(test::scene_path("flexible_pendulum"),
                              {"flex_body.beam.material.youngs_modulus=5e8", "solver.dt=8e-6",
                               "solver.end_time=1.1"});
  // a mark on the hub one metre out along its x axis gives the hub's angle in double precision
  ProbeDef mark;
  mark.name = "hub_mark";
  mark.body = "hub";
  mark.point = Vec2(1.0, 0.0);
  scene.probes.push_back(mark);

  // closed form for the rigid bar with the beam's outline, pivoting about the joint point:
  // T = 4 sqrt(I_O / (m g d)) K(sin(theta0 / 2)), I_O / m = (w^2 + h^2) / 12 + d^2
  const FlexBodyDef& beam = scene.flex_bodies.at(0);
  const Vec2 pivot = joint_named(scene, "pivot").point_i;
  const Vec2 arm = beam.shape.center - pivot;
  const double d = arm.norm();
  const double w = beam.shape.width, h = beam.shape.height;
  const double radius_of_gyration2 = (w * w + h * h) / 12.0 + d * d;
  const double g = -scene.gravity.y();
  const double theta0 = std::atan2(arm.x(), -arm.y());  // from the downward vertical
  const double modulus = std::sin(0.5 * theta0);
  const double period = 4.0 * std::sqrt(radius_of_gyration2 / (g * d)) * elliptic_k(modulus * modulus);
  ASSERT_GT(period, 1.0);
  ASSERT_LT(period, 1.1 * 4.0 / 3.0 * scene.solver.end_time);  // three quarters fit in the run

  Simulation sim(scene);
  sim.initialize();
  const int cx = test::probe_column(sim, "hub_mark", "x");
  const int cy = test::probe_column(sim, "hub_mark", "y");
  ASSERT_GE(cx, 0);
  ASSERT_GE(cy, 0);

  // the beam's swing angle psi from the downward vertical, through the hub's rotation
  const double hub_angle0 = 0.0;
  const double beam_angle0 = theta0;
  auto swing = [&](const Sample& s) {
    const double hub = std::atan2(s.probe_values[cy] - pivot.y(), s.probe_values[cx] - pivot.x());
    return beam_angle0 + (hub - hub_angle0);
  };

  // times at which psi crosses zero: T/4 (falling) and 3T/4 (returning)
  std::vector<double> crossings;
  double t_prev = 0.0, psi_prev = swing(sim.sample());
  while (sim.time() < scene.solver.end_time && crossings.size() < 2) {
    sim.step();
    const Sample s = sim.sample();
    const double psi = swing(s);
    if ((psi_prev > 0.0) != (psi > 0.0)) crossings.push_back(test::crossing_time(t_prev, psi_prev, s.time, psi, 0.0));
    t_prev = s.time;
    psi_prev = psi;
  }
  ASSERT_EQ(crossings.size(), 2u) << "the beam did not swing through the vertical twice";

  // 1 %: the elastic beam differs from the rigid bar by about (f_swing / f_bending)^2 ~ 1e-4 and the
  // particle grid's second moment by dx^2 / (6 I_O / m) ~ 5e-5; 1 % leaves room for neither to matter
  const double quarter = crossings[0];
  const double half = crossings[1] - crossings[0];
  RecordProperty("period_closed_form", test::sci(period));
  RecordProperty("period_from_quarter", test::sci(4.0 * quarter));
  RecordProperty("period_from_half", test::sci(2.0 * half));
  EXPECT_NEAR(4.0 * quarter, period, 0.01 * period);
  EXPECT_NEAR(2.0 * half, period, 0.01 * period);
}

// The slider-crank with its steel rod at 200 rad/s: slider position against the rigid closed form
// x = r cos(theta) + sqrt(l^2 - (r sin(theta) - e)^2), and the attached particles against the
// positions their virtual bodies carry them to.
class StiffSliderCrank : public ::testing::Test {
 protected:
  static constexpr double kOmega = 200.0;

  void SetUp() override {
    scene_ = load_scene(test::scene_path("flexible_slider_crank"), {"flex_body.rod.fracture=false"});
    // spin the crank at kOmega from the vertical start, with the consistent initial velocities
    // (the rod translates at -r omega at that instant)
    for (DriverDef& d : scene_.drivers) d.function.rate = kOmega;
    const Vec2 pivot = joint_named(scene_, "main_bearing").point_i;
    const BodyDef& crank = body_named(scene_, "crank");
    crank_pin_ = crank.position + rotation(crank.angle) * joint_named(scene_, "crank_pin").point_i;
    r_ = (crank_pin_ - pivot).norm();
    const Vec2 translation = kOmega * perp(crank_pin_ - pivot);
    for (BodyDef& b : scene_.bodies) {
      if (b.name == "crank") {
        b.angular_velocity = kOmega;
        b.velocity = kOmega * perp(b.position - pivot);
      } else {
        b.velocity = translation;
      }
    }
    scene_.flex_bodies.at(0).velocity = translation;
    l_ = (body_named(scene_, "rod_right").position - body_named(scene_, "rod_left").position).norm();
    e_ = body_named(scene_, "slider").position.y() - pivot.y();
    x0_ = pivot.x();
  }

  double slider_closed_form(double t) const {
    const double theta = 0.5 * kPi + kOmega * t;
    return x0_ + r_ * std::cos(theta) + std::sqrt(l_ * l_ - std::pow(r_ * std::sin(theta) - e_, 2));
  }

  SceneDef scene_;
  Vec2 crank_pin_ = Vec2::Zero();
  double r_ = 0.0, l_ = 0.0, e_ = 0.0, x0_ = 0.0;
};

TEST_F(StiffSliderCrank, SliderFollowsTheRigidClosedFormAndGripsHoldTheRodEnds) {
  Simulation sim(scene_);
  sim.initialize();
  const int cx = test::probe_column(sim, "slider", "x");
  ASSERT_GE(cx, 0);

  // elastic shortening of the rod under the largest inertia load, F = (m_slider + m_rod) r omega^2
  // (1 + r / l), is F l / (E A); three times that bounds the dynamic amplification of a load
  // applied over a half turn (at most 2) with room for the peridynamic surface softening
  const FlexBodyDef& rod = scene_.flex_bodies.at(0);
  const double area = rod.shape.height * rod.thickness;
  const double rod_mass = rod.material.density * rod.shape.width * area;
  const double force = (body_named(scene_, "slider").mass + rod_mass) * r_ * kOmega * kOmega * (1.0 + r_ / l_);
  const double tolerance = 3.0 * force * l_ / (rod.material.youngs_modulus * area);
  ASSERT_LT(tolerance, 1e-3);  // still a sharp test against a stroke of 2 r = 0.2 m

  // reference pose of every body and the attached particles of every attachment
  Snapshot snap;
  sim.fill_snapshot(snap);
  const SceneGeometry& geometry = *snap.geometry;
  struct Grip {
    int body_slot = -1;       // index into Snapshot::bodies
    Vec2 r0;
    double phi0 = 0.0;
    std::vector<int> particles;
  };
  std::vector<Grip> grips;
  for (const AttachmentDef& a : scene_.attachments) {
    Grip grip;
    for (size_t k = 0; k < geometry.bodies.size(); ++k) {
      if (geometry.bodies[k].name == a.body) grip.body_slot = static_cast<int>(k);
    }
    const BodyDef& body = body_named(scene_, a.body);
    grip.r0 = body.position;
    grip.phi0 = body.angle;
    for (size_t p = 0; p < geometry.reference_x.size(); ++p) {
      if (a.region.contains(Vec2(geometry.reference_x[p], geometry.reference_y[p]))) grip.particles.push_back(int(p));
    }
    ASSERT_GE(grip.body_slot, 0);
    ASSERT_FALSE(grip.particles.empty());
    grips.push_back(grip);
  }

  double worst_slider = 0.0, worst_grip = 0.0, travelled_min = 1e9, travelled_max = -1e9;
  const double end = kPi / kOmega;  // half a turn: the slider runs in past its inner dead centre
  test::run_until(sim, end, 400, [&](Simulation& s) {
    const Sample sample = s.sample();
    const double x = sample.probe_values[cx];
    worst_slider = std::max(worst_slider, std::abs(x - slider_closed_form(sample.time)));
    travelled_min = std::min(travelled_min, x);
    travelled_max = std::max(travelled_max, x);
    s.fill_snapshot(snap);
    for (const Grip& grip : grips) {
      const Snapshot::Pose& pose = snap.bodies[grip.body_slot];
      for (int p : grip.particles) {
        const Vec2 local = rotation(grip.phi0).transpose() *
                           (Vec2(geometry.reference_x[p], geometry.reference_y[p]) - grip.r0);
        const Vec2 target = Vec2(pose.x, pose.y) + rotation(pose.angle) * local;
        worst_grip = std::max(worst_grip, (target - Vec2(snap.px[p], snap.py[p])).norm());
      }
    }
  });
  RecordProperty("slider_worst_error", test::sci(worst_slider));
  RecordProperty("slider_tolerance", test::sci(tolerance));
  RecordProperty("grip_worst_error", test::sci(worst_grip));
  EXPECT_LT(worst_slider, tolerance);
  EXPECT_GT(travelled_max - travelled_min, 0.5 * r_);  // it really moved (about 1.2 r in this half turn)
  // Baumgarte keeps the attachments within 1 um (2.5e-4 of the 4 mm spacing); the snapshot's float
  // positions themselves carry about 3e-8 m
  EXPECT_LT(worst_grip, 1e-6);
}

}  // namespace
}  // namespace periflex
