// The Kalthoff-Winkler experiment (scenes/kalthoff_winkler.toml and its rigid-projectile twin
// scenes/kalthoff_winkler_projectile.toml) on a coarse grid (dx = 1 mm, 10000 particles, a
// horizon of 3 mm): the crack must leave the notch tip at the experiment's angle.
//
// The angle is measured from the damage field at the end (90 us): the cracked particles
// (damage >= 0.35, about half their bonds gone), in their reference places, 6 to 30 mm above the
// notch line (past two horizons of the tip's own damage, and above the short second crack that
// leaves the tip downwards) and right of 5 mm behind the tip; the angle is that of the straight
// line that fits them best (the principal axis of their second moments), against the notch line.
// The crack turns at the tip within a horizon and runs straight after it, so the fit is the
// direction it leaves in, without the few millimetres by which its start sits off the tip.
//
// Tolerance: 60 to 75 degrees. The experiment gives about 70; peridynamic computations report 65
// to 72 at finer grids. The angle grows as the grid is refined: measured 62.5 degrees at 1 mm
// (this test, either load), 64.3 (prescribed velocity) and 65.7 (projectile) at the scene's
// 0.5 mm (PERIFLEX_KW_FULL=1), so the coarse grid reads low by the few degrees that halving dx
// moves it, and the lower bound sits that far under the published band. A crack along the notch
// line (mode-II shear) would read 0 to 20 degrees, one straight up 90: the band tells the
// tensile kink from either.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"

namespace periflex {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct CrackAngle {
  double degrees = 0.0;
  int particles = 0;  // cracked particles the fit used
};

// Runs the scene to its end at dx = 1 mm and fits the crack direction from the notch tip.
// PERIFLEX_KW_FULL=1 runs the scene as written (dx = 0.5 mm).
CrackAngle crack_angle(const std::string& file) {
  std::vector<std::string> overrides{"flex_body.plate.grid_spacing=1e-3", "solver.dt=1.2e-7"};
  if (std::getenv("PERIFLEX_KW_FULL") != nullptr) overrides.clear();
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + file, overrides);
  Simulation sim(scene);
  sim.initialize();
  sim.advance_to(scene.solver.end_time);
  Snapshot snap;
  sim.fill_snapshot(snap);
  const SceneGeometry& geo = *snap.geometry;
  const double tip_x = 0.05, tip_y = 0.025;
  // the cracked particles 6 to 30 mm above the notch line, right of 5 mm behind the tip
  std::vector<double> xs, ys;
  for (size_t i = 0; i < snap.damage.size(); ++i) {
    const double x = geo.reference_x[i], y = geo.reference_y[i];
    if (snap.damage[i] >= 0.35f && y - tip_y >= 0.006 && y - tip_y <= 0.03 && x > tip_x - 0.005) {
      xs.push_back(x);
      ys.push_back(y);
    }
  }
  CrackAngle out;
  out.particles = static_cast<int>(xs.size());
  if (xs.empty()) return out;
  // the line that fits them best: the principal axis of their second moments about their centroid,
  // at 0.5 atan2(2 sxy, sxx - syy) to the notch line
  double mx = 0.0, my = 0.0;
  for (size_t k = 0; k < xs.size(); ++k) {
    mx += xs[k] / xs.size();
    my += ys[k] / xs.size();
  }
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (size_t k = 0; k < xs.size(); ++k) {
    sxx += (xs[k] - mx) * (xs[k] - mx);
    sxy += (xs[k] - mx) * (ys[k] - my);
    syy += (ys[k] - my) * (ys[k] - my);
  }
  out.degrees = 0.5 * std::atan2(2.0 * sxy, sxx - syy) * 180.0 / kPi;
  if (out.degrees < 0.0) out.degrees += 180.0;
  return out;
}

TEST(KalthoffWinkler, CrackLeavesTheNotchAtTheExperimentsAngleUnderPrescribedVelocity) {
  const CrackAngle a = crack_angle("kalthoff_winkler.toml");
  std::printf("Kalthoff-Winkler, prescribed velocity: crack at %.1f degrees (%d particles)\n", a.degrees,
              a.particles);
  RecordProperty("angle_degrees", std::to_string(a.degrees));
  ASSERT_GE(a.particles, 20) << "no crack from the notch tip";
  EXPECT_GT(a.degrees, 60.0);
  EXPECT_LT(a.degrees, 75.0);
}

TEST(KalthoffWinkler, CrackLeavesTheNotchAtTheExperimentsAngleUnderARigidProjectile) {
  const CrackAngle a = crack_angle("kalthoff_winkler_projectile.toml");
  std::printf("Kalthoff-Winkler, rigid projectile: crack at %.1f degrees (%d particles)\n", a.degrees,
              a.particles);
  RecordProperty("angle_degrees", std::to_string(a.degrees));
  ASSERT_GE(a.particles, 20) << "no crack from the notch tip";
  EXPECT_GT(a.degrees, 60.0);
  EXPECT_LT(a.degrees, 75.0);
}

}  // namespace
}  // namespace periflex
