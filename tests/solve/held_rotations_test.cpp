// Point masses whose angle no constraint sees: a zero-inertia bob on a massless rod (the IFToMM
// A01 pendulum as first written, with no extra massless link) and a point mass pinned at its own
// origin. Their angles are held at the initial value and the rest of the motion is exact; a
// spin or a torque on such a body is refused, naming the body.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "study/elliptic.h"

namespace periflex {
namespace {

std::string data_scene(const std::string& name) {
  return std::string(PERIFLEX_SOURCE_ROOT) + "/tests/data/scenes/" + name;
}

// The A01 bob on a 1 m rod from rest horizontal: theta from the downward vertical,
// sin(theta / 2) = k cd(omega0 t | k^2), k = sin(45 deg), omega0^2 = g / L.
Vec2 a01_exact(double t) {
  const double k = std::sin(kPi / 4), omega0 = std::sqrt(9.81);
  const JacobiValues j = jacobi_elliptic(omega0 * t, k * k);
  const double theta = 2.0 * std::asin(k * j.cn / j.dn);
  return {std::sin(theta), -std::cos(theta)};
}

TEST(HeldRotations, PointMassOnMasslessRodFollowsTheExactPendulum) {
  const SceneDef scene = load_scene(data_scene("a01_point_mass_rod.toml"));
  Simulation sim(scene);
  sim.initialize();
  // one degree of freedom: the rod's angle (x, y, phi less the rod's equation less the held phi)
  EXPECT_EQ(sim.info().degrees_of_freedom, 1);
  double worst = 0.0;
  // every 0.037 s (not a multiple of dt) over 10 s, about five swings
  for (int k = 1; k * 0.037 <= 10.0; ++k) {
    const double t = k * 0.037;
    sim.advance_to(t);
    const auto p = sim.sample().probe_values;  // x, y, vx, vy, angle, omega
    const Vec2 exact = a01_exact(t);
    worst = std::max(worst, std::hypot(p[0] - exact.x(), p[1] - exact.y()));
    ASSERT_EQ(p[4], 0.0) << "the held angle moved at t = " << t;
  }
  std::printf("A01 as a point mass on a massless rod, rk4 dt 1e-3, 10 s: max error %.3g m\n", worst);
  EXPECT_LT(worst, 1e-8);
}

TEST(HeldRotations, PointMassPinnedAtItsOriginStaysAndCarriesItsLoad) {
  const SceneDef scene = load_scene(data_scene("point_mass_pinned.toml"));
  Simulation sim(scene);
  sim.initialize();
  EXPECT_EQ(sim.info().degrees_of_freedom, 1);
  double worst_balance = 0.0;
  for (int k = 1; k <= 20; ++k) {
    sim.advance_to(0.05 * k);
    const Sample s = sim.sample();
    // knot: x, y, vx, vy, angle, omega; then bob
    EXPECT_EQ(s.probe_values[0], 0.0);
    EXPECT_EQ(s.probe_values[1], 0.0);
    EXPECT_EQ(s.probe_values[4], 0.3);
    EXPECT_NEAR(std::hypot(s.probe_values[6], s.probe_values[7]), 1.0, 1e-10);
    worst_balance = std::max(worst_balance, std::abs(s.energies.balance));
  }
  // the bob swings from (0.6, -0.8) and the energy balance holds
  EXPECT_LT(worst_balance, 1e-8);
}

// The A01 scene text with one line added to the bob's table or one element at the end.
std::string a01_with(const std::string& body_line, const std::string& tail = "") {
  return "[scene]\nname = \"x\"\ngravity = [0.0, -9.81]\n[solver]\nintegrator = \"rk4\"\ndt = 1e-3\n"
         "end_time = 1.0\n[[body]]\nname = \"bob\"\nmass = 1.0\ninertia = 0.0\nposition = [1.0, 0.0]\n" +
         body_line + "\n[[joint]]\nname = \"rod\"\ntype = \"revolute_revolute\"\nbody_i = \"ground\"\n"
                     "body_j = \"bob\"\n" + tail;
}

TEST(HeldRotations, SpinOfAHeldAngleIsRefusedAtTheBody) {
  const SceneDef scene = parse_scene(a01_with("angular_velocity = 2.0"), "spin.toml");
  try {
    Simulation sim(scene);
    sim.initialize();
    FAIL() << "a spinning point mass was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().key, "body.bob.angular_velocity") << e.what();
    EXPECT_GT(e.where().line, 0) << e.what();
  }
}

TEST(HeldRotations, TorqueOnAHeldAngleIsRefused) {
  // a spring pulling a point off the origin at its free length: no torque until the angle turns
  const std::string tail =
      "[[force]]\nname = \"twist\"\ntype = \"spring_damper\"\nbody_i = \"ground\"\nbody_j = \"bob\"\n"
      "point_i = [1.0, 1.0]\npoint_j = [0.0, 0.5]\nstiffness = 10.0\n";
  const SceneDef scene = parse_scene(a01_with("", tail), "twist.toml");
  try {
    Simulation sim(scene);
    sim.initialize();
    FAIL() << "a torque on a point mass was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'twist' puts a torque on body 'bob'"), std::string::npos) << e.what();
  }
  // the same spring at the mass point turns nothing: accepted
  const std::string centred =
      "[[force]]\nname = \"pull\"\ntype = \"spring_damper\"\nbody_i = \"ground\"\nbody_j = \"bob\"\n"
      "point_i = [1.0, 1.0]\nstiffness = 10.0\n";
  Simulation ok(parse_scene(a01_with("", centred), "pull.toml"));
  EXPECT_NO_THROW(ok.initialize());
}

}  // namespace
}  // namespace periflex
