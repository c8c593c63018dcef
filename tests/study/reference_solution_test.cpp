// The exact references against independent answers: a tightly integrated pendulum ODE and the
// textbook slider-crank position formula.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "study/reference_solution.h"

namespace periflex {
namespace {

const char* kPendulum = R"(
[scene]
gravity = [0.0, -9.81]
[solver]
end_time = 2.0
[[body]]
name = "bar"
mass = 2.0
inertia = 0.1
position = [0.5, 0.0]
angle = 0.0
[[joint]]
name = "pin"
type = "revolute"
body_i = "ground"
body_j = "bar"
point_i = [0.0, 0.0]
point_j = [-0.5, 0.0]
[[probe]]
name = "tip"
body = "bar"
point = [0.5, 0.0]
)";

// theta'' = -w^2 sin(theta) by classical RK4 at a tiny step: an answer independent of the elliptic form
double pendulum_angle_by_rk4(double theta0, double w2, double t_end) {
  const int n = 200000;
  const double h = t_end / n;
  double th = theta0, om = 0.0;
  const auto acc = [&](double x) { return -w2 * std::sin(x); };
  for (int i = 0; i < n; ++i) {
    const double k1t = om, k1o = acc(th);
    const double k2t = om + 0.5 * h * k1o, k2o = acc(th + 0.5 * h * k1t);
    const double k3t = om + 0.5 * h * k2o, k3o = acc(th + 0.5 * h * k2t);
    const double k4t = om + h * k3o, k4o = acc(th + h * k3t);
    th += h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    om += h / 6.0 * (k1o + 2 * k2o + 2 * k3o + k4o);
  }
  return th;
}

TEST(PendulumExact, MatchesTightlyIntegratedEquationOfMotion) {
  const SceneDef scene = parse_scene(kPendulum, "pendulum.toml");
  const auto ref = make_pendulum_exact(scene);
  // horizontal start: theta0 = 90 degrees from hanging; w^2 = m g d / (I + m d^2)
  const double w2 = 2.0 * 9.81 * 0.5 / (0.1 + 2.0 * 0.25);
  for (double t : {0.3, 1.1, 1.9}) {
    const double theta = pendulum_angle_by_rk4(kPi / 2.0, w2, t);
    // the tip lies on the arm at distance 1 from the pin, at angle theta from straight down
    const std::vector<double> p = ref->probe_values(t);
    ASSERT_EQ(p.size(), 2u);
    // RK4 at h = 1e-5 has global error ~1e-17 * t; 1e-10 leaves room for round-off of both
    EXPECT_NEAR(p[0], std::sin(theta), 1e-10) << "t = " << t;
    EXPECT_NEAR(p[1], -std::cos(theta), 1e-10) << "t = " << t;
  }
  // at t = 0 the probe is where the scene puts it
  const std::vector<double> p0 = ref->probe_values(0.0);
  EXPECT_NEAR(p0[0], 1.0, 1e-14);
  EXPECT_NEAR(p0[1], 0.0, 1e-14);
}

TEST(PendulumExact, RefusesAScenePushedOffRest) {
  EXPECT_THROW(make_pendulum_exact(parse_scene(kPendulum, "p.toml", {"body.bar.angular_velocity=1"})), InputError);
}

const char* kSliderCrank = R"(
[scene]
gravity = [0.0, -9.81]
[[body]]
name = "crank"
mass = 1.0
inertia = 0.01
position = [0.1, 0.0]
[[body]]
name = "rod"
mass = 2.0
inertia = 0.1
position = [0.5, 0.0]
[[body]]
name = "slider"
mass = 1.0
inertia = 0.01
position = [0.8, 0.0]
[[joint]]
name = "base"
type = "revolute"
body_i = "ground"
body_j = "crank"
point_i = [0.0, 0.0]
point_j = [-0.1, 0.0]
[[joint]]
name = "crank_rod"
type = "revolute"
body_i = "crank"
body_j = "rod"
point_i = [0.1, 0.0]
point_j = [-0.3, 0.0]
[[joint]]
name = "rod_slider"
type = "revolute"
body_i = "rod"
body_j = "slider"
point_i = [0.3, 0.0]
point_j = [0.0, 0.0]
[[joint]]
name = "guide"
type = "translational"
body_i = "ground"
body_j = "slider"
point_i = [0.0, 0.0]
point_j = [0.0, 0.0]
axis_i = [1.0, 0.0]
axis_j = [1.0, 0.0]
[[driver]]
name = "motor"
type = "absolute_angle"
body_i = "crank"
function = { type = "rate", value = 0.0, rate = 6.0 }
[[probe]]
name = "slider"
body = "slider"
point = [0.0, 0.0]
[[probe]]
name = "crank_pin"
body = "crank"
point = [0.1, 0.0]
[[probe]]
name = "rod_mid"
body = "rod"
point = [0.0, 0.0]
)";

TEST(SliderCrankExact, MatchesTheTextbookPositionFormula) {
  const SceneDef scene = parse_scene(kSliderCrank, "slider_crank.toml");
  const auto ref = make_slider_crank_exact(scene);
  const double r = 0.2, l = 0.6;
  for (double t : {0.0, 0.2, 0.5, 0.9}) {
    const double phi = 6.0 * t;
    const std::vector<double> p = ref->probe_values(t);
    ASSERT_EQ(p.size(), 6u);
    // in-line slider: x_B = r cos(phi) + sqrt(l^2 - r^2 sin^2(phi)); round-off only
    const double xb = r * std::cos(phi) + std::sqrt(l * l - r * r * std::sin(phi) * std::sin(phi));
    EXPECT_NEAR(p[0], xb, 1e-12) << "t = " << t;
    EXPECT_NEAR(p[1], 0.0, 1e-12);
    EXPECT_NEAR(p[2], r * std::cos(phi), 1e-12);
    EXPECT_NEAR(p[3], r * std::sin(phi), 1e-12);
    // rod centre: midway between the crank pin and the slider pin
    EXPECT_NEAR(p[4], 0.5 * (r * std::cos(phi) + xb), 1e-12);
    EXPECT_NEAR(p[5], 0.5 * r * std::sin(phi), 1e-12);
  }
}

TEST(SliderCrankExact, RefusesAPendulum) {
  EXPECT_THROW(make_slider_crank_exact(parse_scene(kPendulum, "p.toml")), InputError);
}

}  // namespace
}  // namespace periflex
