// Contact between two rigid bodies' shapes ([[contact]] type = "rigid"), run by the program:
// each check against an answer of rigid-body impact theory.
//  - A disc dropped on a massless anvil welded to the ground rebounds at the speed the law's
//    restitution gives: e = 1 keeps the speed; e = 0.5 against the same spring-dashpot law
//    integrated apart, in the test, at a thousandth of the step (the law cannot pull, so it lets
//    go a little before the spring is unloaded and its rebound is a few percent above the e it
//    was set from; docs/contact.md gives both).
//  - Two discs in a head-on collision (1 kg at 2 m/s, 3 kg at -1 m/s, e = 1) leave at the
//    velocities of the elastic impact, -2.5 and 0.5 m/s; momentum is kept to round-off.
//  - A box strikes the corner of a free box off-centre (polygon against polygon): both turn,
//    momentum and angular momentum are kept, the energy balance closes.
//  - Two boxes crossed like a plus sign, no corner of either inside the other, are pushed apart
//    the shallower way by the two corners of the clipped manifold and give back all the energy
//    stored in them; a bar across a box, and two bars crossed like a plus sign, with both ends of
//    each outside the other, part the same way; two bars crossed deep at 45 degrees part too,
//    turning, with the balance closed.
//  - A step too large for the stiffness is refused before the run, naming the key; a rigid
//    contact without stiffness, or of a body with itself, is refused naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "core/vec2.h"

#include "../cli/run_output_files.h"
#include "../cli/run_program.h"
#include "contact_scenes.h"

namespace periflex {
namespace {

using testing::fresh_directory;
using testing::read_series;
using testing::run_periflex;
using testing::Series;

// One free body per entry, with a probe at its centre, and the contact `contact` between them.
std::string body(const std::string& name, double mass, double inertia, double x, double y, double vx, double vy,
                 const std::string& shape) {
  char text[1024];
  std::snprintf(text, sizeof text,
                "[[body]]\nname = \"%s\"\nmass = %.17g\ninertia = %.17g\nposition = [%.17g, %.17g]\n"
                "velocity = [%.17g, %.17g]\nshape = %s\n[[probe]]\nname = \"%s\"\nbody = \"%s\"\n",
                name.c_str(), mass, inertia, x, y, vx, vy, shape.c_str(), name.c_str(), name.c_str());
  return text;
}

std::string header(double dt, double end) {
  char text[512];
  std::snprintf(text, sizeof text,
                "[scene]\nname = \"rigid_contact\"\ngravity = [0, 0]\n[solver]\nintegrator = \"verlet\"\n"
                "dt = %.17g\nend_time = %.17g\noutput_interval = 1e-4\n",
                dt, end);
  return text;
}

std::string contact(const std::string& a, const std::string& b, double k, double e, const std::string& extra = "") {
  char text[512];
  std::snprintf(text, sizeof text,
                "[[contact]]\nname = \"touch\"\ntype = \"rigid\"\nbody_i = \"%s\"\nbody_j = \"%s\"\n"
                "stiffness = %.17g\nrestitution = %.17g\n%s",
                a.c_str(), b.c_str(), k, e, extra.c_str());
  return text;
}

// Runs the scene text; returns its series (exit code 0 expected).
Series run_scene(const std::string& name, const std::string& text) {
  const auto dir = fresh_directory("rigid_contact_" + name);
  const std::string path = test::write_scene(dir, name + ".toml", text);
  const auto run = run_periflex("run " + path + " --quiet --out " + (dir / "out").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return read_series(dir / "out" / "series.csv");
}

double largest_of(const Series& s, const std::string& column) {
  double m = -INFINITY;
  for (const auto& row : s.rows) m = std::max(m, row[s.column(column)]);
  return m;
}

// A massless anvil (a box welded to the ground) and a 1 kg disc 1 mm above it at 1 m/s down,
// Verlet at dt (5.5 us: 570 steps over the 3.1 ms contact).
std::string drop_scene(double e, double dt = 5.5e-6) {
  return header(dt, 0.02) +
         body("disc", 1.0, 1.25e-3, 0.0, 0.051, 0.0, -1.0, "{ type = \"circle\", radius = 0.05 }") +
         "[[body]]\nname = \"anvil\"\nmass = 0\ninertia = 0\nposition = [0, -0.05]\n"
         "shape = { type = \"box\", width = 0.2, height = 0.1 }\n"
         "[[joint]]\nname = \"weld\"\ntype = \"rigid\"\nbody_i = \"ground\"\nbody_j = \"anvil\"\n"
         "point_i = [0, -0.05]\n" +
         contact("disc", "anvil", 1e6, e);
}

// The rebound of a unit mass at 1 m/s on the law F = max(0, k d + c d_dot), integrated apart
// with classical RK4 at step h until it lets go.
double reference_rebound(double k, double e, double h) {
  const double log_e = std::log(e), zeta = -log_e / std::sqrt(M_PI * M_PI + log_e * log_e);
  const double c = 2.0 * zeta * std::sqrt(k);
  // state: depth d, its rate w; d'' = -max(0, k d + c w)
  const auto acc = [&](double d, double w) { return -std::max(0.0, k * d + c * w); };
  double d = 0.0, w = 1.0;
  for (int n = 0; n < 100000000; ++n) {
    const double k1d = w, k1w = acc(d, w);
    const double k2d = w + 0.5 * h * k1w, k2w = acc(d + 0.5 * h * k1d, w + 0.5 * h * k1w);
    const double k3d = w + 0.5 * h * k2w, k3w = acc(d + 0.5 * h * k2d, w + 0.5 * h * k2w);
    const double k4d = w + h * k3w, k4w = acc(d + h * k3d, w + h * k3w);
    d += h / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
    w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if (w < 0.0 && (d <= 0.0 || k * d + c * w <= 0.0)) return -w;
  }
  return NAN;
}

TEST(RigidContact, DiscOnAnAnvilReboundsAtTheSpeedOfTheLaw) {
  for (double e : {1.0, 0.5}) {
    SCOPED_TRACE(e);
    const Series s = run_scene(e == 1.0 ? "drop_elastic" : "drop_damped", drop_scene(e));
    ASSERT_GT(s.rows.size(), 10u);
    const auto& last = s.rows.back();
    EXPECT_EQ(last[s.column("contact_count")], 0.0);  // it has left
    const double rebound = last[s.column("probe.disc.vy")];
    const double expected = reference_rebound(1e6, e, 1e-8);
    std::printf("disc on anvil, e = %.2f: rebound %.5f m/s, law integrated apart %.5f m/s\n", e, rebound, expected);
    EXPECT_NEAR(rebound, expected, 0.005 * expected);
    if (e == 1.0) {
      EXPECT_NEAR(rebound, 1.0, 0.005);
    }
    // nothing pushed it sideways or turned it
    EXPECT_NEAR(last[s.column("probe.disc.vx")], 0.0, 1e-12);
    EXPECT_NEAR(last[s.column("probe.disc.omega")], 0.0, 1e-12);
    // the damping's work is counted: the balance closes to 0.2% of the initial energy (it is
    // first order in dt, as the dissipated energy is summed step by step: 0.23% at 11 us, 0.12%
    // at 5.5 us, 0.06% at 2.75 us)
    for (const auto& row : s.rows) EXPECT_LT(std::abs(row[s.column("energy_balance")]), 2e-3 * 0.5) << row[0];
  }
}

TEST(RigidContact, HeadOnDiscsExchangeTheMomentumOfAnElasticImpact) {
  const std::string text = header(1.1e-5, 0.01) +
                           body("a", 1.0, 1.25e-3, -0.0505, 0.0, 2.0, 0.0, "{ type = \"circle\", radius = 0.05 }") +
                           body("b", 3.0, 3.75e-3, 0.0505, 0.0, -1.0, 0.0, "{ type = \"circle\", radius = 0.05 }") +
                           contact("a", "b", 1e6, 1.0);
  const Series s = run_scene("head_on", text);
  ASSERT_GT(s.rows.size(), 10u);
  const auto& last = s.rows.back();
  EXPECT_EQ(last[s.column("contact_count")], 0.0);
  EXPECT_NEAR(last[s.column("probe.a.vx")], -2.5, 0.005);
  EXPECT_NEAR(last[s.column("probe.b.vx")], 0.5, 0.005);
  for (const auto& row : s.rows) {
    EXPECT_NEAR(row[s.column("probe.a.vx")] + 3.0 * row[s.column("probe.b.vx")], -1.0, 1e-12) << row[0];
    EXPECT_LT(std::abs(row[s.column("energy_balance")]), 1e-3 * 6.5) << row[0];
  }
}

// Two free 1 kg bodies crossed, k = 1e4 N/m, e = 1, for 0.05 s: "lower" lying along x at the
// origin, "upper" with its middle 5 mm higher. Checks what every such crossing must do: `points`
// contacts at the start (the manifold's) and none at the end; apart (upper's lowest point,
// `upper_reach` below its middle, above lower's top 10 mm above its own) with upper moving up and
// lower down; momentum kept to round-off at every row; and the energy stored in the overlap,
// `stored` (k d^2 / 2 summed over the points), given back: the balance within 1% of it at every
// row, the kinetic energy at the end within 1% of it (the law is conservative while the same
// features touch; Verlet's own energy error at 30 us is far below that). Returns the run's
// series for a case's own checks.
Series crossed_pair_parts(const std::string& name, const std::string& lower_shape, double lower_inertia,
                          const std::string& upper_shape, double upper_inertia, double upper_reach, int points,
                          double stored) {
  const std::string text = header(3e-5, 0.05) + body("lower", 1.0, lower_inertia, 0.0, 0.0, 0.0, 0.0, lower_shape) +
                           body("upper", 1.0, upper_inertia, 0.0, 0.005, 0.0, 0.0, upper_shape) +
                           contact("lower", "upper", 1e4, 1.0);
  const Series s = run_scene(name, text);
  EXPECT_GT(s.rows.size(), 10u);
  if (s.rows.empty()) return s;
  const auto& last = s.rows.back();
  EXPECT_EQ(s.rows.front()[s.column("contact_count")], points);
  EXPECT_EQ(last[s.column("contact_count")], 0.0);
  const double gap = (last[s.column("probe.upper.y")] - upper_reach) - (last[s.column("probe.lower.y")] + 0.01);
  double kinetic = 0.0, worst_balance = 0.0;
  for (const char* b : {"lower", "upper"}) {
    const std::string p = std::string("probe.") + b + ".";
    kinetic += 0.5 * (std::pow(last[s.column(p + "vx")], 2) + std::pow(last[s.column(p + "vy")], 2));
  }
  for (const auto& row : s.rows) worst_balance = std::max(worst_balance, std::abs(row[s.column("energy_balance")]));
  std::printf("%s: gap at the end %.4f m, speeds %.4f and %.4f m/s, kinetic %.4f J of %.4f J stored, "
              "largest |balance| %.3g J\n",
              name.c_str(), gap, last[s.column("probe.upper.vy")], last[s.column("probe.lower.vy")], kinetic, stored,
              worst_balance);
  EXPECT_GT(gap, 0.0);
  EXPECT_GT(last[s.column("probe.upper.vy")], 0.0);
  EXPECT_LT(last[s.column("probe.lower.vy")], 0.0);
  EXPECT_LT(worst_balance, 0.01 * stored);
  EXPECT_NEAR(kinetic, stored, 0.01 * stored);
  for (const auto& row : s.rows) {
    EXPECT_NEAR(row[s.column("probe.upper.vy")] + row[s.column("probe.lower.vy")], 0.0, 1e-12);
    EXPECT_NEAR(row[s.column("probe.upper.vx")] + row[s.column("probe.lower.vx")], 0.0, 1e-12);
  }
  return s;
}

TEST(RigidContact, BoxesCrossedLikeAPlusSignArePushedApartAlongTheShallowerWay) {
  // a 200 x 20 mm box across a 20 x 60 mm box 5 mm above its middle: no corner of either lies
  // inside the other. The tall box's bottom face lies 35 mm under the long box's top (45 mm
  // downwards, 110 mm sideways): its two corners, 35 mm deep each, push it up and the long one
  // down, without turning, and give back the 2 x k d^2 / 2 = 12.25 J stored in them
  const Series s = crossed_pair_parts("plus_sign", "{ type = \"box\", width = 0.2, height = 0.02 }",
                                      1.0 / 12.0 * (0.04 + 0.0004), "{ type = \"box\", width = 0.02, height = 0.06 }",
                                      1.0 / 12.0 * (0.0004 + 0.0036), 0.03, 2, 2 * 0.5 * 1e4 * 0.035 * 0.035);
  for (const auto& row : s.rows) EXPECT_NEAR(row[s.column("probe.upper.omega")], 0.0, 1e-9);
}

TEST(RigidContact, BarAcrossABoxWithBothEndsOutsideIsPushedApartLikeTheBox) {
  // the plus sign again with the long box made a bar of the same size (ends at +-0.1 m, 20 mm
  // wide): both bar ends lie far outside the tall box and no corner of the box lies inside the
  // bar. The box's bottom face lies 35 mm inside the bar's straight part, as in the long box, so
  // they separate the same way
  const Series s = crossed_pair_parts(
      "bar_across_box", "{ type = \"bar\", p1 = [-0.1, 0.0], p2 = [0.1, 0.0], width = 0.02 }",
      1.0 / 12.0 * (0.04 + 0.0004), "{ type = \"box\", width = 0.02, height = 0.06 }", 1.0 / 12.0 * (0.0004 + 0.0036),
      0.03, 2, 2 * 0.5 * 1e4 * 0.035 * 0.035);
  for (const auto& row : s.rows) EXPECT_NEAR(row[s.column("probe.upper.omega")], 0.0, 1e-9);
}

TEST(RigidContact, BarsCrossedLikeAPlusSignArePushedApartWithoutTurning) {
  // a bar along x across a bar along y: each bar's end centres lie 35 mm or more from the
  // other's core, more than the two radii (20 mm). The upright bar's lower end centre lies 35 mm
  // under the flat bar's core: one contact, 55 mm deep (65 mm downwards, 120 mm sideways). The
  // upright bar's lowest point is its core end (40 mm) plus its radius below its middle
  const Series s = crossed_pair_parts(
      "bars_crossed", "{ type = \"bar\", p1 = [-0.1, 0.0], p2 = [0.1, 0.0], width = 0.02 }", 1.0 / 12.0 * 0.04,
      "{ type = \"bar\", p1 = [0.0, -0.04], p2 = [0.0, 0.04], width = 0.02 }", 1.0 / 12.0 * 0.01, 0.05, 1,
      0.5 * 1e4 * 0.055 * 0.055);
  for (const auto& row : s.rows) EXPECT_NEAR(row[s.column("probe.upper.omega")], 0.0, 1e-9);
}

TEST(RigidContact, BarsCrossedDeepAtFortyFiveDegreesSeparateAndGiveBackTheStoredEnergy) {
  // the upright bar of the plus sign tilted to 45 degrees (end centres 80 mm apart, at
  // (-28.3, -23.3) and (28.3, 33.3) mm from the flat bar's middle): deep in the flat bar with
  // neither end within reach of the other's core. Its lower end centre lies 23.3 mm under the
  // flat bar's core, 43.3 mm deeper than the two radii: one contact pushing it up there, off its
  // middle, so it turns as it rises. They must part and give back the 9.37 J stored: kinetic
  // energy of both bodies' motion and turning at the end against k d^2 / 2, the balance within 1%
  // of it at every row, momentum and angular momentum kept to round-off
  const double c = 0.04 * std::sqrt(0.5), depth = 0.02 + (c - 0.005);
  const double i_flat = 1.0 / 12.0 * 0.04, i_tilted = 1.0 / 12.0 * 0.0064;
  char tilted[256];
  std::snprintf(tilted, sizeof tilted, "{ type = \"bar\", p1 = [%.17g, %.17g], p2 = [%.17g, %.17g], width = 0.02 }", -c,
                -c, c, c);
  const std::string text =
      header(3e-5, 0.05) +
      body("lower", 1.0, i_flat, 0.0, 0.0, 0.0, 0.0, "{ type = \"bar\", p1 = [-0.1, 0.0], p2 = [0.1, 0.0], width = 0.02 }") +
      body("upper", 1.0, i_tilted, 0.0, 0.005, 0.0, 0.0, tilted) + contact("lower", "upper", 1e4, 1.0);
  const Series s = run_scene("bars_crossed_45", text);
  ASSERT_GT(s.rows.size(), 10u);
  const double stored = 0.5 * 1e4 * depth * depth;
  const auto& first = s.rows.front();
  const auto& last = s.rows.back();
  EXPECT_EQ(first[s.column("contact_count")], 1.0);
  EXPECT_EQ(last[s.column("contact_count")], 0.0);
  // apart: the distance between the two cores where the bodies are at the end exceeds the radii
  const auto core = [&](const char* b, const Vec2& p) {
    const std::string q = std::string("probe.") + b + ".";
    return Vec2(last[s.column(q + "x")], last[s.column(q + "y")]) + rotation(last[s.column(q + "angle")]) * p;
  };
  const Vec2 a0 = core("lower", Vec2(-0.1, 0.0)), a1 = core("lower", Vec2(0.1, 0.0));
  const Vec2 b0 = core("upper", Vec2(-c, -c)), b1 = core("upper", Vec2(c, c));
  const auto to_segment = [](const Vec2& p, const Vec2& u, const Vec2& v) {
    const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
    return (p - (u + t * (v - u))).norm();
  };
  const double separation =
      std::min({to_segment(a0, b0, b1), to_segment(a1, b0, b1), to_segment(b0, a0, a1), to_segment(b1, a0, a1)});
  double kinetic = 0.0, worst_balance = 0.0;
  for (const auto& [b, inertia] : {std::pair<const char*, double>{"lower", i_flat}, {"upper", i_tilted}}) {
    const std::string p = std::string("probe.") + b + ".";
    kinetic += 0.5 * (std::pow(last[s.column(p + "vx")], 2) + std::pow(last[s.column(p + "vy")], 2)) +
               0.5 * inertia * std::pow(last[s.column(p + "omega")], 2);
  }
  const auto angular = [&](const std::vector<double>& r) {
    double l = 0.0;
    for (const auto& [b, inertia] : {std::pair<const char*, double>{"lower", i_flat}, {"upper", i_tilted}}) {
      const std::string p = std::string("probe.") + b + ".";
      l += r[s.column(p + "x")] * r[s.column(p + "vy")] - r[s.column(p + "y")] * r[s.column(p + "vx")] +
           inertia * r[s.column(p + "omega")];
    }
    return l;
  };
  for (const auto& row : s.rows) {
    worst_balance = std::max(worst_balance, std::abs(row[s.column("energy_balance")]));
    EXPECT_NEAR(row[s.column("probe.upper.vx")] + row[s.column("probe.lower.vx")], 0.0, 1e-12) << row[0];
    EXPECT_NEAR(row[s.column("probe.upper.vy")] + row[s.column("probe.lower.vy")], 0.0, 1e-12) << row[0];
    EXPECT_NEAR(angular(row), angular(first), 1e-12) << row[0];
  }
  std::printf("bars crossed at 45 degrees: core distance at the end %.4f m (radii 0.02), kinetic %.4f J of %.4f J "
              "stored, largest |balance| %.3g J, upper turning at %.3f rad/s\n",
              separation, kinetic, stored, worst_balance, last[s.column("probe.upper.omega")]);
  EXPECT_GT(separation, 0.02);
  EXPECT_GT(last[s.column("probe.upper.vy")], 0.0);
  EXPECT_LT(worst_balance, 0.01 * stored);
  EXPECT_NEAR(kinetic, stored, 0.01 * stored);
}

TEST(RigidContact, BoxStrikingABoxOffCentreKeepsMomentumAndAngularMomentum) {
  // a 100 x 50 mm box at 1 m/s strikes, with its lower right corner, the upper left corner of
  // a free 200 x 100 mm box, with friction: both turn
  const std::string text =
      header(5.5e-6, 0.02) +
      body("a", 1.0, 1.0 / 12.0 * (0.01 + 0.0025), -0.1504, 0.07, 1.0, 0.0,
           "{ type = \"box\", width = 0.1, height = 0.05 }") +
      body("b", 4.0, 4.0 / 12.0 * (0.04 + 0.01), 0.0, 0.0, 0.0, 0.0, "{ type = \"box\", width = 0.2, height = 0.1 }") +
      contact("a", "b", 1e6, 0.7, "friction = 0.3\n");
  const Series s = run_scene("boxes", text);
  ASSERT_GT(s.rows.size(), 10u);
  const double ia = 1.0 / 12.0 * 0.0125, ib = 4.0 / 12.0 * 0.05;
  const auto momentum = [&](const std::vector<double>& r, const char* axis) {
    return 1.0 * r[s.column(std::string("probe.a.v") + axis)] + 4.0 * r[s.column(std::string("probe.b.v") + axis)];
  };
  const auto angular = [&](const std::vector<double>& r) {
    double l = 0.0;
    for (const auto& [name, m, i] : {std::tuple<const char*, double, double>{"a", 1.0, ia}, {"b", 4.0, ib}}) {
      const std::string p = std::string("probe.") + name + ".";
      l += m * (r[s.column(p + "x")] * r[s.column(p + "vy")] - r[s.column(p + "y")] * r[s.column(p + "vx")]) +
           i * r[s.column(p + "omega")];
    }
    return l;
  };
  const auto& first = s.rows.front();
  const auto& last = s.rows.back();
  EXPECT_GT(largest_of(s, "contact_count"), 0.0);
  EXPECT_EQ(last[s.column("contact_count")], 0.0);
  // the struck box moves off and both turn
  EXPECT_GT(last[s.column("probe.b.vx")], 0.05);
  EXPECT_GT(std::abs(last[s.column("probe.a.omega")]), 0.1);
  EXPECT_GT(std::abs(last[s.column("probe.b.omega")]), 0.1);
  for (const auto& row : s.rows) {
    EXPECT_NEAR(momentum(row, "x"), momentum(first, "x"), 1e-12) << row[0];
    EXPECT_NEAR(momentum(row, "y"), momentum(first, "y"), 1e-12) << row[0];
    EXPECT_NEAR(angular(row), angular(first), 1e-12) << row[0];
    EXPECT_LT(std::abs(row[s.column("energy_balance")]), 2e-3 * 0.5) << row[0];
  }
}

TEST(RigidContact, BadDeclarationsAndAnUnstableStepAreRefusedNamingTheKey) {
  const auto dir = fresh_directory("rigid_contact_bad");
  // a step above the contact's critical step (sqrt(2 m / k) at the disc's rim: 0.8 ms at 1e6 N/m)
  std::string text = drop_scene(1.0, 2e-3);
  auto run = run_periflex("run " + test::write_scene(dir, "unstable.toml", text) + " --quiet --out " +
                          (dir / "o1").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("contact.touch.stiffness"), std::string::npos) << run.output;
  // no stiffness
  text = drop_scene(1.0);
  text.replace(text.find("stiffness = 1000000\n"), 20, "");
  run = run_periflex("check " + test::write_scene(dir, "no_stiffness.toml", text));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("stiffness"), std::string::npos) << run.output;
  // a body with itself
  text = drop_scene(1.0);
  text.replace(text.find("body_j = \"anvil\"\nstiffness"), 16, "body_j = \"disc\"\n");
  run = run_periflex("check " + test::write_scene(dir, "itself.toml", text));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("body_j"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace periflex
