// The GPU bond forces (gpu/gl_bond_force_device.h) against the CPU loops of the same body: forces
// of every shipped bond-based scene's body, the bonds an evaluation breaks, the row maxima of the
// break pass after the step, and the bonds a short notched-plate run breaks. Run under whatever
// OpenGL the machine has (Mesa llvmpipe in CI); skipped, saying why, where no OpenGL 4.3 compute
// context with fp64 can be made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <filesystem>
#include <numbers>
#include <memory>
#include <string>
#include <vector>

#include "core/resources.h"
#include "gpu/gl_bond_force_device.h"
#include "pd/pd_body.h"
#include "scene/scene_loader.h"
#include "solve/sim_state.h"
#include "solve/simulation.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

// The compute context every test here shares; null, with why in `reason`, where none can be made.
std::shared_ptr<GlComputeContext> compute_context(std::string& reason) {
  static std::shared_ptr<GlComputeContext> context;
  static std::string why;
  static bool tried = false;
  if (!tried) {
    tried = true;
    try {
      context = std::make_shared<GlComputeContext>(find_resource_root());
    } catch (const std::exception& e) {
      why = e.what();
    }
  }
  reason = why;
  return context;
}

#define REQUIRE_COMPUTE_CONTEXT(context)                                                       \
  std::string why_not;                                                                         \
  auto context = compute_context(why_not);                                                     \
  if (!context) GTEST_SKIP() << "no OpenGL compute context with fp64 here: " << why_not

// The largest magnitude of v.
double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// A smooth displacement and velocity field over the body, so that bonds stretch by up to `strain`
// and stretch at up to `rate` per second along both axes (cosines of the position over the
// body's extent): forces and damping are well above round-off everywhere.
void displaced_state(const PdBody& body, double strain, double rate, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  const std::vector<double>& x = body.reference_positions();
  const int n = body.particle_count();
  double lo_x = x[0], hi_x = x[0], lo_y = x[1], hi_y = x[1];
  for (int i = 0; i < n; ++i) {
    lo_x = std::min(lo_x, x[2 * i]), hi_x = std::max(hi_x, x[2 * i]);
    lo_y = std::min(lo_y, x[2 * i + 1]), hi_y = std::max(hi_y, x[2 * i + 1]);
  }
  const double size = std::max({hi_x - lo_x, hi_y - lo_y, body.grid_spacing()});
  const double wave = 2.0 * std::numbers::pi / size;  // strain = amplitude * wave
  q.resize(2 * n);
  qd.resize(2 * n);
  for (int i = 0; i < n; ++i) {
    const double px = x[2 * i] - lo_x, py = x[2 * i + 1] - lo_y;
    q[2 * i] = x[2 * i] + strain / wave * std::sin(wave * px) * (1.0 + 0.3 * std::cos(wave * py));
    q[2 * i + 1] = x[2 * i + 1] + 0.5 * strain / wave * std::sin(wave * py + 0.7);
    qd[2 * i] = rate / wave * std::cos(1.3 * wave * py);
    qd[2 * i + 1] = rate / wave * std::sin(0.9 * wave * px);
  }
}

// A body of `def` on the CPU and the same on the GPU.
struct BodyPair {
  std::unique_ptr<PdBody> cpu, gpu;
};
BodyPair build_pair(const FlexBodyDef& def, const std::shared_ptr<GlComputeContext>& context,
                    unsigned groups_across = 65535, DevicePrecision precision = DevicePrecision::kFp64) {
  BodyPair pair{PdBody::build(def, 0), PdBody::build(def, 0)};
  pair.gpu->use_bond_force_device(std::make_unique<GlBondForceDevice>(context, precision, groups_across));
  return pair;
}

// Adds both bodies' forces at (q, qd, t = 0) and compares them: within 1e-12 of the largest force.
// Why 1e-12: the CPU sums a row's bonds in vector lanes, the GPU one after another, each a sum of
// at most a few dozen terms rounded to 1.1e-16 each, so they differ by some 1e-15 of the row's
// largest term; 1e-12 leaves a margin of hundreds and still catches any term wrong or missing.
// (fp32: see ForcesOfFp32AreWithinSinglePrecision for its tolerance, given here.)
void expect_same_forces(BodyPair& pair, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& what,
                        double tolerance = 1e-12) {
  Eigen::VectorXd cpu = Eigen::VectorXd::Zero(q.size()), gpu = Eigen::VectorXd::Zero(q.size());
  pair.cpu->add_forces(q, qd, 0.0, cpu);
  pair.gpu->add_forces(q, qd, 0.0, gpu);
  const double scale = max_abs(cpu);
  ASSERT_GT(scale, 0.0) << what;
  EXPECT_LE(max_abs(gpu - cpu), tolerance * scale) << what << ": largest force " << scale;
  // the same bonds broken in the evaluation, with the same energy booked for them
  EXPECT_EQ(pair.gpu->broken_bond_count(), pair.cpu->broken_bond_count()) << what;
  EXPECT_TRUE(pair.gpu->bond_state().broken == pair.cpu->bond_state().broken) << what;
  const FractureUpdate cpu_breaks = pair.cpu->take_evaluation_breaks(), gpu_breaks = pair.gpu->take_evaluation_breaks();
  EXPECT_EQ(gpu_breaks.bonds_broken, cpu_breaks.bonds_broken) << what;
  EXPECT_EQ(gpu_breaks.energy_released, cpu_breaks.energy_released) << what;
}

// Every flexible body of every shipped scene whose law is bond-based, at a displaced state where
// bonds stretch up to twice their critical stretch (so that the evaluation breaks some), without
// and then with bond damping.
TEST(GlBondForceDevice, ForcesEqualTheCpuLoopsOnEveryShippedBondBasedBody) {
  REQUIRE_COMPUTE_CONTEXT(context);
  int bodies = 0, breaking = 0;
  for (const auto& entry : fs::directory_iterator(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const SceneDef scene = load_scene(entry.path().string());
    for (const FlexBodyDef& def : scene.flex_bodies) {
      if (def.material.model != PdMaterialDef::Model::kBondBased) continue;
      const std::string what = entry.path().filename().string() + " body " + def.name;
      BodyPair pair = build_pair(def, context);
      ASSERT_NE(pair.gpu->bond_force_device(), nullptr);
      const double s0 = pair.cpu->critical_stretch();
      const double strain = std::isfinite(s0) ? 2.0 * s0 : 1e-3;
      Eigen::VectorXd q, qd;
      displaced_state(*pair.cpu, strain, 10.0, q, qd);
      pair.cpu->set_bond_damping(0.0);
      pair.gpu->set_bond_damping(0.0);
      expect_same_forces(pair, q, qd, what + ", elastic");
      // eta / E = 1e-4 s at a strain rate of 10 /s: damping as large as the elastic part
      const double eta = 1e-4 * def.material.youngs_modulus;
      pair.cpu->set_bond_damping(eta);
      pair.gpu->set_bond_damping(eta);
      displaced_state(*pair.cpu, 1.1 * strain, 10.0, q, qd);
      expect_same_forces(pair, q, qd, what + ", damped");
      ++bodies;
      if (pair.cpu->broken_bond_count() > 0) ++breaking;
    }
  }
  // the shipped scenes hold a dozen such bodies, most of them breakable
  EXPECT_GE(bodies, 10);
  EXPECT_GE(breaking, 5);
}

// A body of more rows than one axis of a dispatch holds (beyond 4.2M particles: 65535 groups of
// 64) continues on the second axis. The notched plate's 4,000 rows laid 7 groups across, so that
// the last row of groups is partly empty: every row's force as the CPU's.
TEST(GlBondForceDevice, RowsBeyondOneAxisOfGroupsContinueOnTheNext) {
  REQUIRE_COMPUTE_CONTEXT(context);
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml");
  BodyPair pair = build_pair(scene.flex_bodies.at(0), context, 7);
  Eigen::VectorXd q, qd;
  displaced_state(*pair.cpu, 1.5 * pair.cpu->critical_stretch(), 10.0, q, qd);
  expect_same_forces(pair, q, qd, "notched plate, 7 groups across");
}

// fp32, the displacement form, on every shipped bond-based body at a smooth state below s0 (no
// bond near its break, where the two precisions may decide apart): forces within 2e-5 of the
// largest force. Why 2e-5: each term carries the rounding of a few single-precision operations
// (6e-8 each) on the displacement and the reference vector, a row sums up to 28 of them, and the
// forces of interior rows are differences of such sums. Measured under llvmpipe: at most 2.0e-6
// (glass branching), 1.1e-6 (Kalthoff-Winkler), so the bound leaves a margin of 10; forces from
// absolute positions in fp32 would be off by about 1e-2, which this catches.
TEST(GlBondForceDevice, ForcesOfFp32AreWithinSinglePrecision) {
  REQUIRE_COMPUTE_CONTEXT(context);
  int bodies = 0;
  for (const auto& entry : fs::directory_iterator(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const SceneDef scene = load_scene(entry.path().string());
    for (const FlexBodyDef& def : scene.flex_bodies) {
      if (def.material.model != PdMaterialDef::Model::kBondBased) continue;
      const std::string what = entry.path().filename().string() + " body " + def.name + ", fp32";
      BodyPair pair = build_pair(def, context, 65535, DevicePrecision::kFp32);
      const double s0 = pair.cpu->critical_stretch();
      const double strain = std::isfinite(s0) ? 0.5 * s0 : 1e-3;
      Eigen::VectorXd q, qd;
      displaced_state(*pair.cpu, strain, 10.0, q, qd);
      expect_same_forces(pair, q, qd, what, 2e-5);
      const double eta = 1e-4 * def.material.youngs_modulus;
      pair.cpu->set_bond_damping(eta);
      pair.gpu->set_bond_damping(eta);
      expect_same_forces(pair, q, qd, what + ", damped", 2e-5);
      ++bodies;
    }
  }
  EXPECT_GE(bodies, 10);
}

// Bonds that break after the step (the timing of integrators with trial stages): the GPU's row
// maxima feed the break pass at the same positions, which breaks the same bonds.
TEST(GlBondForceDevice, RowMaximaGiveTheSameBreaksAfterTheStep) {
  REQUIRE_COMPUTE_CONTEXT(context);
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml");
  BodyPair pair = build_pair(scene.flex_bodies.at(0), context);
  pair.cpu->set_break_timing(PdBody::BreakTiming::kAfterStep);
  pair.gpu->set_break_timing(PdBody::BreakTiming::kAfterStep);
  Eigen::VectorXd q, qd;
  displaced_state(*pair.cpu, 1.5 * pair.cpu->critical_stretch(), 10.0, q, qd);
  expect_same_forces(pair, q, qd, "notched plate, every bond held");
  EXPECT_EQ(pair.cpu->broken_bond_count(), 0);
  const FractureUpdate cpu = pair.cpu->update_fracture(q), gpu = pair.gpu->update_fracture(q);
  EXPECT_GT(cpu.bonds_broken, 0);
  EXPECT_EQ(gpu.bonds_broken, cpu.bonds_broken);
  EXPECT_EQ(gpu.energy_released, cpu.energy_released);
  EXPECT_TRUE(pair.gpu->bond_state().broken == pair.cpu->bond_state().broken);
  // the breaks made on the host reach the GPU's copy: the next forces leave them out alike
  expect_same_forces(pair, q, qd, "notched plate, after the break pass");
}

// The notched plate torn by its grips, 300 steps on each path (its fracture energy lowered a
// hundredfold so that the crack starts within them): the same bonds broken, step by step the same
// count, and positions that agree to round-off grown over the run.
TEST(GlBondForceDevice, NotchedPlateBreaksTheSameBondsOnBothPaths) {
  REQUIRE_COMPUTE_CONTEXT(context);
  install_bond_force_device(gl_bond_force_device_factory(find_resource_root()));
  SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                              {"flex_body.plate.material.fracture_energy=3"});
  Simulation cpu(scene);
  scene.solver.device = "gpu";
  Simulation gpu(scene);
  cpu.initialize();
  gpu.initialize();
  const Eigen::VectorXd start = cpu.coordinates();
  long broken = 0;
  SimState cpu_state, gpu_state;
  for (int step = 1; step <= 300; ++step) {
    cpu.step();
    gpu.step();
    ASSERT_EQ(gpu.sample().broken_bonds, cpu.sample().broken_bonds) << "step " << step;
    broken = cpu.sample().broken_bonds;
  }
  cpu.save_state(cpu_state);
  gpu.save_state(gpu_state);
  ASSERT_EQ(gpu_state.flex.size(), 1u);
  EXPECT_TRUE(gpu_state.flex[0].broken_bits == cpu_state.flex[0].broken_bits);
  EXPECT_GT(broken, 20) << "the crack did not start within the run";
  // positions: the runs differ only by the order of each row's sum, grown over 300 steps
  const double travel = max_abs(cpu.coordinates() - start);
  EXPECT_LE(max_abs(gpu.coordinates() - cpu.coordinates()), 1e-9 * travel);
  install_bond_force_device({});
}

// The particles a run left damaged (damage > 0), as indices.
std::vector<int> damaged_particles(const Simulation& sim) {
  Snapshot snapshot;
  sim.fill_snapshot(snapshot);
  std::vector<int> out;
  for (size_t p = 0; p < snapshot.damage.size(); ++p)
    if (snapshot.damage[p] > 0.0f) out.push_back(static_cast<int>(p));
  return out;
}

// Glass branching to its end in fp32 on the GPU against fp64 on the CPU: the crack's path, as the
// sets of damaged particles, with a Jaccard index (shared over either) of at least 0.95. fp32's
// stretch is within about 1e-7 of fp64's, so a bond within that of s0 may break a step apart, and
// the crack's instability may grow that into another branch; 0.95 allows a few particles at the
// branch tips and catches a crack that takes another way.
TEST(GlBondForceDevice, Fp32GlassCrackFollowsFp64) {
  REQUIRE_COMPUTE_CONTEXT(context);
  install_bond_force_device(gl_bond_force_device_factory(find_resource_root()));
  SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/glass_branching.toml");
  Simulation fp64(scene);
  scene.solver.device = "gpu";
  scene.solver.precision = "fp32";
  Simulation fp32(scene);
  for (Simulation* sim : {&fp64, &fp32}) {
    sim->initialize();
    while (sim->time() < sim->end_time() * (1.0 - 1e-12)) sim->step();
  }
  const std::vector<int> a = damaged_particles(fp64), b = damaged_particles(fp32);
  std::vector<int> shared, either;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(either));
  ASSERT_GT(a.size(), 1000u) << "the glass did not crack";
  const double jaccard = static_cast<double>(shared.size()) / static_cast<double>(either.size());
  EXPECT_GE(jaccard, 0.95) << shared.size() << " of " << either.size() << " damaged particles shared";
  RecordProperty("jaccard", std::to_string(jaccard));
  install_bond_force_device({});
}

}  // namespace
}  // namespace periflex::testing
