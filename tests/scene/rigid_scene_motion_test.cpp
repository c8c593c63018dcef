// The rigid scenes shipped in scenes/ move as their comments promise: each is run and compared
// with a closed-form answer worked out independently of the program. These catch a wrong
// length, mass or initial configuration typed into a scene file.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

// Full precision for the recorded properties.
std::string text(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

std::string scene_path(const char* name) { return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + name; }

// Runs `scene` until `until`, calling `visit(time, columns)` after every step.
void run(const SceneDef& scene, double until,
         const std::function<void(double, const std::map<std::string, double>&)>& visit) {
  Simulation sim(scene);
  sim.initialize();
  const std::vector<std::string> names = sim.probe_columns();
  std::map<std::string, double> columns;
  while (sim.time() < until) {
    sim.step();
    const Sample sample = sim.sample();
    for (size_t k = 0; k < names.size(); ++k) columns[names[k]] = sample.probe_values[k];
    visit(sample.time, columns);
  }
}

// Released from 60 degrees, the swing takes T = 4 sqrt(L/g) K(sin 30 deg) = 2.152874666880516 s
// (K by the arithmetic-geometric mean; L = 1 m, g = 9.81 m/s^2).
TEST(RigidSceneMotion, PendulumPeriodMatchesEllipticIntegral) {
  const double expected_period = 2.152874666880516;
  const SceneDef scene = load_scene(scene_path("pendulum.toml"));
  // the bob crosses x = 0 at T/4 (going left) and 3T/4 (going right)
  std::vector<double> crossings;
  double last_t = 0.0, last_x = std::sin(kPi / 3.0);
  run(scene, 0.8 * expected_period, [&](double t, const std::map<std::string, double>& c) {
    const double x = c.at("probe.bob.x");
    if ((last_x > 0.0) != (x > 0.0)) crossings.push_back(last_t + (t - last_t) * last_x / (last_x - x));
    last_t = t;
    last_x = x;
  });
  ASSERT_EQ(crossings.size(), 2u);
  ::testing::Test::RecordProperty("measured_period", text(2.0 * (crossings[1] - crossings[0])));
  // 1e-4 s: linear interpolation between 1 ms samples at the fastest point of the swing and
  // Baumgarte's small constraint drift; rk4's own period error at this step is ~1e-10 s
  EXPECT_NEAR(crossings[0], expected_period / 4.0, 1e-4);
  EXPECT_NEAR(crossings[1] - crossings[0], expected_period / 2.0, 1e-4);
}

// Slider position x = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta)), theta = 2 pi t, r = 0.1, l = 0.3.
TEST(RigidSceneMotion, SliderCrankStrokeMatchesClosedForm) {
  const SceneDef scene = load_scene(scene_path("slider_crank.toml"));
  const double r = 0.1, l = 0.3;
  double worst = 0.0, lowest = 1.0, highest = 0.0;
  run(scene, 1.0, [&](double t, const std::map<std::string, double>& c) {
    const double theta = 2.0 * kPi * t;
    const double expected = r * std::cos(theta) + std::sqrt(l * l - r * r * std::sin(theta) * std::sin(theta));
    const double x = c.at("probe.slider.x");
    worst = std::max(worst, std::abs(x - expected));
    lowest = std::min(lowest, x);
    highest = std::max(highest, x);
  });
  ::testing::Test::RecordProperty("max_stroke_error", text(worst));
  // 1e-6 m: a fully driven mechanism; what remains is constraint drift held by Baumgarte
  EXPECT_LT(worst, 1e-6);
  // the stroke spans l - r .. l + r (to the sampling of the dead centres: 1 ms at 1 rev/s)
  EXPECT_NEAR(lowest, l - r, 1e-4);
  EXPECT_NEAR(highest, l + r, 1e-4);
}

// Grashof crank-rocker: the rocker's limits are where crank and coupler line up, |O2 B| = b -/+ a,
// giving psi = pi - acos((c^2 + d^2 - e^2) / (2 c d)) for the upper assembly branch.
TEST(RigidSceneMotion, FourBarRockerSwingsBetweenToggleLimits) {
  const SceneDef scene = load_scene(scene_path("four_bar.toml"));
  const double a = 0.1, b = 0.4, c = 0.3, d = 0.35;
  auto limit = [&](double e) { return kPi - std::acos((c * c + d * d - e * e) / (2.0 * c * d)); };
  const double psi_low = limit(b + a);    // 1.3913 rad: crank and coupler extended
  const double psi_high = limit(b - a);   // 2.1936 rad: crank folded over the coupler
  double lowest = 10.0, highest = -10.0;
  run(scene, 1.0, [&](double, const std::map<std::string, double>& columns) {
    const double psi = columns.at("probe.rocker_tip.angle");
    lowest = std::min(lowest, psi);
    highest = std::max(highest, psi);
  });
  ::testing::Test::RecordProperty("rocker_limits", text(lowest) + " " + text(highest));
  // 1e-4 rad: at a limit the rocker is momentarily still, so 1 ms sampling misses the extreme
  // by about psi'' dt^2 / 2 < 1e-5 rad; constraint drift adds less
  EXPECT_NEAR(lowest, psi_low, 1e-4);
  EXPECT_NEAR(highest, psi_high, 1e-4);
}

// The double pendulum is chaotic, but rk4 at 1 ms keeps its energy: released horizontal, the
// drop of potential energy must reappear as kinetic energy over the whole 10 s run.
TEST(RigidSceneMotion, DoublePendulumConservesEnergyOverTheRun) {
  const SceneDef scene = load_scene(scene_path("double_pendulum.toml"));
  Simulation sim(scene);
  sim.initialize();
  // scale: the most potential energy the bars can give up, both hanging straight down:
  // m g (0.5 m + 1.5 m) with m = 1 kg = 19.62 J
  const double scale = 9.81 * (0.5 + 1.5);
  double worst = 0.0;
  while (sim.time() < scene.solver.end_time) {
    sim.step();
    worst = std::max(worst, std::abs(sim.sample().energies.balance));
  }
  ::testing::Test::RecordProperty("max_energy_balance", text(worst));
  // 1e-4 of the energy exchanged: rk4's local error at dt = 1 ms is far below this, but the
  // Baumgarte terms and the close passes of the chaotic motion cost some accuracy
  EXPECT_LT(worst / scale, 1e-4);
}

}  // namespace
}  // namespace periflex
