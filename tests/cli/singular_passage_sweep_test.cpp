// Every integrator and every constraint correction the program offers, through the singular
// positions of the IFToMM A02 double four-bar, at step sizes that divide the output interval and
// ones that do not: each run either stays on the physical branch with exit 0, or stops with exit
// 3 and a diagnostic. A run that leaves the branch and still exits 0 is the one outcome refused.
// On the physical branch the couplers translate (their angle stays 0 whatever the integration
// error), the energy balance stays within 1 % of the potential energy the cranks swing through
// (3.5 g x 2 m = 68.7 J: a jump at a dead point is what a switch of branch shows), and B0
// follows the reference of four_bar_runs.h; the fourth- and fifth-order schemes must follow it
// within 1e-3 m at every step size here, and so must every scheme over one dead point at the
// small steps. (Over 10 s at dt >= 2.5e-3, first- and second-order schemes on the physical
// branch carry a phase error above 1e-3 m: there the couplers' angle and the energy tell.)
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "four_bar_runs.h"
#include "solve/simulation.h"

namespace periflex::testing {
namespace {

const std::vector<std::string> kCorrections = {"none", "baumgarte", "projection"};

// The scene as shipped with probes on the couplers appended (a probe only reads the state).
std::string with_coupler_probes(const std::string& tag, const std::string& scene_file) {
  const auto file = fresh_directory(tag + "_scene") / "scene.toml";
  std::ofstream out(file);
  out << read_text(scene_file);
  for (const char* body : {"coupler1", "coupler2"})
    out << "\n[[probe]]\nname = \"" << body << "\"\nbody = \"" << body << "\"\npoint = [0.0, 0.0]\n";
  return file.string();
}

// Largest |angle| of the couplers over the run (0 on the physical branch), wrapped to [-pi, pi],
// and the largest |energy balance|.
struct BranchSigns {
  double coupler_angle = 1e300, energy_error = 1e300;
};
BranchSigns branch_signs(const std::string& tag) {
  const Series s = read_series(std::filesystem::current_path() / ("cli_test_out_singular_" + tag) / "series.csv");
  BranchSigns out;
  const int e = s.find_column("energy_balance");
  if (e < 0) return out;
  out.coupler_angle = out.energy_error = 0.0;
  for (const auto& row : s.rows) out.energy_error = std::max(out.energy_error, std::abs(row[e]));
  for (const char* body : {"coupler1", "coupler2"}) {
    const int c = s.find_column(std::string("probe.") + body + ".angle");
    if (c < 0) return BranchSigns{};
    for (const auto& row : s.rows)
      out.coupler_angle = std::max(out.coupler_angle, std::abs(std::remainder(row[c], 2.0 * kPi)));
  }
  return out;
}
constexpr double kEnergyBound = 0.01 * 3.5 * kFourBarGravity * 2.0;

// Runs every integrator x correction at each step size and checks the outcome of each.
void sweep(const std::string& tag, const std::string& shipped_scene, double theta0, double omega0, double end,
           double every, const std::vector<double>& steps, bool every_scheme_accurate) {
  const auto reference = reference_b0_x(theta0, omega0, end, every);
  const std::string scene_file = with_coupler_probes(tag, shipped_scene);
  int on_branch = 0, stopped = 0;
  for (const std::string& integrator : integrator_names()) {
    for (const std::string& correction : kCorrections) {
      for (double dt : steps) {
        const std::string what = tag + ": " + integrator + " / " + correction + " dt " + exact_text(dt);
        const auto o = run_and_compare(tag, scene_file,
                                       "--integrator " + integrator + " --dt " + exact_text(dt) +
                                           " --set solver.correction.method=" + correction,
                                       reference, every);
        // the methods recommended for mechanisms carry the motion through every dead point
        if (correction == "projection" && (integrator == "rk4" || integrator == "dopri54")) {
          EXPECT_EQ(o.exit_code, 0) << what << ": " << o.output;
        }
        if (o.exit_code == 3) {
          // a numerical stop says what failed, when, and what to try
          EXPECT_NE(o.output.find("numerical failure"), std::string::npos) << what << ": " << o.output;
          EXPECT_NE(o.output.find("Try:"), std::string::npos) << what << ": " << o.output;
          ++stopped;
          continue;
        }
        EXPECT_EQ(o.exit_code, 0) << what << ": " << o.output;
        if (o.exit_code != 0) continue;
        EXPECT_NEAR(o.end_time, end, 1e-9) << what;
        EXPECT_GE(o.compared, 4) << what;
        const BranchSigns signs = branch_signs(tag);
        EXPECT_LT(signs.coupler_angle, 1e-3) << what << " left the physical branch (coupler angle "
                                             << signs.coupler_angle << " rad) and exited 0";
        EXPECT_LT(signs.energy_error, kEnergyBound) << what << " gained or lost energy (" << signs.energy_error
                                                    << " J) and exited 0";
        if (every_scheme_accurate || integrator == "rk4" || integrator == "dopri54") {
          EXPECT_LT(o.max_error, 1e-3) << what << " left the physical path (B0 error " << o.max_error
                                       << " m) and exited 0";
        }
        ++on_branch;
      }
    }
  }
  // the sweep means something only if runs do reach the end
  EXPECT_GT(on_branch, 0) << tag << ": " << stopped << " runs stopped";
}

// The benchmark as shipped, over its whole 10 s (20 dead points), at the larger step sizes;
// 3e-3 and 7e-3 do not divide the output interval of 0.01 s.
TEST(SingularPassageSweep, BenchmarkA02EveryIntegratorAndCorrection) {
  sweep("a02_sweep", scene("benchmarks/a02_double_four_bar.toml"), kPi / 2, -1.0, 10.0, 0.01,
        {2.5e-2, 1e-2, 7e-3, 5e-3, 3e-3, 2.5e-3}, false);
}

// The small step sizes, down to 1.25e-5, through the first dead point of the benchmark's own
// motion (tests/data/scenes/a02_near_dead_point.toml: 0.2 rad before it, 0.1 s); 7e-4, 3e-4 and
// 7e-5 do not divide the output interval of 0.005 s.
TEST(SingularPassageSweep, DeadPointEveryIntegratorAndCorrectionDownToSmallSteps) {
  const double theta0 = 0.2;
  const double omega0 = -std::sqrt((1.5 + 3.5 * kFourBarGravity * (1.0 - std::sin(theta0))) / 1.5);
  sweep("dead_point_sweep", std::string(PERIFLEX_TEST_DATA) + "/scenes/a02_near_dead_point.toml", theta0, omega0,
        0.1, 0.005, {1e-3, 7e-4, 3e-4, 1e-4, 7e-5, 2.5e-5, 1.25e-5}, true);
}

// Symplectic Euler with projection keeps an energy error of its own (bounded, first order in dt)
// that moves across a dead point as much as over as long a span before it. The passage check
// judges the jump against that error, so at small steps the run carries the motion through all
// 20 dead points of the benchmark with exit 0 and B0 on the reference; 3e-4 does not divide the
// output interval of 0.01 s. At a step whose own energy error could hide a switch of branch the
// run stops, saying so.
TEST(SingularPassageSweep, SymplecticEulerWithProjectionPassesEveryDeadPointAtSmallSteps) {
  const double end = 10.0, every = 0.01;
  const auto reference = reference_b0_x(kPi / 2, -1.0, end, every);
  const std::string scene_file = with_coupler_probes("a02_symplectic", scene("benchmarks/a02_double_four_bar.toml"));
  for (double dt : {2.5e-4, 3e-4, 1e-4}) {
    const std::string what = "symplectic_euler / projection dt " + exact_text(dt);
    const auto o = run_and_compare("a02_symplectic", scene_file,
                                   "--integrator symplectic_euler --dt " + exact_text(dt) +
                                       " --set solver.correction.method=projection",
                                   reference, every);
    ASSERT_EQ(o.exit_code, 0) << what << ": " << o.output;
    EXPECT_NEAR(o.end_time, end, 1e-9) << what;
    EXPECT_GE(o.compared, 1000) << what;
    EXPECT_LT(o.max_error, 1e-3) << what << ": B0 error " << o.max_error << " m";
    const BranchSigns signs = branch_signs("a02_symplectic");
    EXPECT_LT(signs.coupler_angle, 1e-3) << what;
    EXPECT_LT(signs.energy_error, kEnergyBound) << what;
  }
  const auto coarse = run_and_compare("a02_symplectic", scene_file,
                                      "--integrator symplectic_euler --dt 0.01 --set solver.correction.method=projection",
                                      reference, every);
  EXPECT_EQ(coarse.exit_code, 3) << coarse.output;
  EXPECT_NE(coarse.output.find("too large to tell"), std::string::npos) << coarse.output;
  EXPECT_NE(coarse.output.find("lower solver.dt"), std::string::npos) << coarse.output;
}

}  // namespace
}  // namespace periflex::testing
