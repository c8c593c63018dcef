// The Kalthoff-Winkler experiment (scenes/kalthoff_winkler.toml and its rigid-projectile twin
// scenes/kalthoff_winkler_projectile.toml) on a coarse grid (dx = 1 mm, 10000 particles, a
// horizon of 3 mm): the crack must kink from the notch tip at the angle measured at that grid.
//
// The angle is measured from the damage field at the end (90 us): the cracked particles
// (damage >= 0.35, about half their bonds gone), in their reference places, 6 to 30 mm above the
// notch line (past two horizons of the tip's own damage, and above the short second crack that
// leaves the tip downwards) and right of 5 mm behind the tip; the angle is that of the straight
// line that fits them best (the principal axis of their second moments), against the notch line.
// The crack turns at the tip within a horizon and runs straight after it, so the fit is the
// direction it leaves in, without the few millimetres by which its start sits off the tip.
//
// Tolerance at dx = 1 mm: 59 to 66 degrees, the angle measured at this grid (62.5 under either
// load) +- 3.5 degrees, a little more than one halving of dx moves it (62.5 -> 64.3 prescribed,
// 62.5 -> 65.7 projectile at 0.5 mm). It is not the experiment's band: the experiment gives about
// 70 and peridynamic computations report 65 to 72 at finer grids, and the angle grows as the grid
// is refined, so this coarse grid reads a few degrees under that band (docs/contact.md gives the
// angle at 1, 0.5 and 0.25 mm). What the band catches: a change of the model that moves the crack
// as much as a refinement does, a mode-II crack along the notch line (0 to 20 degrees) or one
// straight up (90). Run at another grid (PERIFLEX_KW_FULL, PERIFLEX_KW_DX) the test checks only
// that the crack is the tensile kink, 45 to 85 degrees, and prints the angle.
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
// PERIFLEX_KW_FULL=1 runs the scene as written (dx = 0.5 mm); PERIFLEX_KW_DX=<metres> any grid
// whose spacing divides 25 mm into a whole even number, the step scaled with it (1.2e-7 s at 1 mm,
// the ratio of the scenes' own 6e-8 s at 0.5 mm).
bool at_another_grid() { return std::getenv("PERIFLEX_KW_FULL") != nullptr || std::getenv("PERIFLEX_KW_DX") != nullptr; }

// The band the angle must lie in at the grid run (see the top of the file).
void expect_angle_in_band(double degrees) {
  if (at_another_grid()) {
    EXPECT_GT(degrees, 45.0);
    EXPECT_LT(degrees, 85.0);
  } else {
    EXPECT_GT(degrees, 59.0);
    EXPECT_LT(degrees, 66.0);
  }
}

CrackAngle crack_angle(const std::string& file) {
  std::vector<std::string> overrides{"flex_body.plate.grid_spacing=1e-3", "solver.dt=1.2e-7"};
  if (std::getenv("PERIFLEX_KW_FULL") != nullptr) overrides.clear();
  if (const char* dx = std::getenv("PERIFLEX_KW_DX")) {
    char dt[64];
    std::snprintf(dt, sizeof dt, "solver.dt=%.17g", 1.2e-4 * std::atof(dx));
    overrides = {std::string("flex_body.plate.grid_spacing=") + dx, dt};
  }
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

TEST(KalthoffWinkler, CrackKinksFromTheNotchAtTheAngleOfItsGridUnderPrescribedVelocity) {
  const CrackAngle a = crack_angle("kalthoff_winkler.toml");
  std::printf("Kalthoff-Winkler, prescribed velocity: crack at %.1f degrees (%d particles)\n", a.degrees,
              a.particles);
  RecordProperty("angle_degrees", std::to_string(a.degrees));
  ASSERT_GE(a.particles, 20) << "no crack from the notch tip";
  expect_angle_in_band(a.degrees);
}

TEST(KalthoffWinkler, CrackKinksFromTheNotchAtTheAngleOfItsGridUnderARigidProjectile) {
  const CrackAngle a = crack_angle("kalthoff_winkler_projectile.toml");
  std::printf("Kalthoff-Winkler, rigid projectile: crack at %.1f degrees (%d particles)\n", a.degrees,
              a.particles);
  RecordProperty("angle_degrees", std::to_string(a.degrees));
  ASSERT_GE(a.particles, 20) << "no crack from the notch tip";
  expect_angle_in_band(a.degrees);
}

}  // namespace
}  // namespace periflex
