// Simulation::save_state / restore_state hold everything the next step reads: N steps, save,
// M steps, restore, M steps again gives every coordinate, bond and account bit for bit, both in
// the same Simulation (bonds broken since the save heal) and in a fresh one built from the scene
// (what a restart from a checkpoint does). Scenes: a rigid mechanism through singular positions,
// a coupled plate that cracks, both plate models (state-based included), the glass plate (coarse
// grid, shortened) at one and two threads, and two discs in particle contact.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "../contact/contact_scenes.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

std::string shipped(const std::string& name) { return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + name; }

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every field two states must share after the same steps from the same state.
void expect_same(const SimState& a, const SimState& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(same_bits(a.time, b.time)) << a.time << " vs " << b.time;
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_TRUE(same_bits(a.q, b.q)) << "positions differ, max " << (a.q - b.q).cwiseAbs().maxCoeff();
  EXPECT_TRUE(same_bits(a.qd, b.qd)) << "velocities differ, max " << (a.qd - b.qd).cwiseAbs().maxCoeff();
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(a.work[k], b.work[k])) << "work " << k;
  EXPECT_TRUE(same_bits(a.fracture_energy, b.fracture_energy));
  EXPECT_EQ(a.broken_bonds, b.broken_bonds);
  ASSERT_EQ(a.flex.size(), b.flex.size());
  for (size_t f = 0; f < a.flex.size(); ++f) {
    EXPECT_EQ(a.flex[f].broken_bits, b.flex[f].broken_bits) << "broken bonds of body " << f;
    EXPECT_EQ(a.flex[f].weighted_volume, b.flex[f].weighted_volume);
  }
  EXPECT_EQ(a.rank.dropped, b.rank.dropped);
  EXPECT_EQ(a.rank.rank_changes, b.rank.rank_changes);
}

struct Continuation {
  SimState saved, first, again, fresh;
};

// n steps, save, m steps (first), restore, m steps (again); a fresh Simulation restored from the
// save, m steps (fresh).
Continuation continue_twice(const SceneDef& scene, long n, long m) {
  Continuation c;
  Simulation sim(scene);
  for (long k = 0; k < n; ++k) sim.step();
  sim.save_state(c.saved);
  for (long k = 0; k < m; ++k) sim.step();
  sim.save_state(c.first);
  sim.restore_state(c.saved);
  for (long k = 0; k < m; ++k) sim.step();
  sim.save_state(c.again);
  Simulation other(scene);
  other.restore_state(c.saved);
  for (long k = 0; k < m; ++k) other.step();
  other.save_state(c.fresh);
  return c;
}

void expect_repeats(const Continuation& c) {
  expect_same(c.first, c.again, "restored in the same simulation");
  expect_same(c.first, c.fresh, "restored in a fresh simulation");
}

TEST(SimState, RigidMechanismThroughSingularPositionsRepeatsBitForBit) {
  // the double four-bar passes a singular position every half second: the rows left out change
  // (rank monitoring) on both sides of the save
  for (const char* integrator : {"rk4", "dopri54"}) {
    SCOPED_TRACE(integrator);
    const SceneDef scene = load_scene(shipped("benchmarks/a02_double_four_bar.toml"),
                                      {std::string("solver.integrator=\"") + integrator + "\""});
    const Continuation c = continue_twice(scene, 1234, 1500);
    EXPECT_GT(c.first.rank.rank_changes, c.saved.rank.rank_changes);
    expect_repeats(c);
  }
}

TEST(SimState, CrackingCoupledPlateRepeatsBitForBit) {
  // saved while the crack runs, so the steps after it break more bonds (and the restore in the
  // same simulation heals them)
  const SceneDef scene = load_scene(shipped("notched_plate.toml"));
  const Continuation c = continue_twice(scene, 1700, 150);
  EXPECT_GT(c.saved.broken_bonds, 0);
  EXPECT_GT(c.first.broken_bonds, c.saved.broken_bonds);
  expect_repeats(c);
}

TEST(SimState, BothPlateModelsRepeatBitForBit) {
  // a bond-based and a state-based plate side by side, saved after both began to crack
  const SceneDef scene = load_scene(shipped("notched_plate_models.toml"));
  const Continuation c = continue_twice(scene, 700, 100);
  EXPECT_GT(c.saved.broken_bonds, 0);
  EXPECT_GT(c.first.broken_bonds, c.saved.broken_bonds);
  expect_repeats(c);
}

TEST(SimState, GlassPlateRepeatsBitForBitOnOneAndTwoThreads) {
  // the coarse grid of the scene's own comment, saved as the crack runs
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    const SceneDef scene = load_scene(shipped("glass_branching.toml"),
                                      {"flex_body.plate.grid_spacing=5e-4", "flex_body.plate.horizon_ratio=3",
                                       "solver.dt=5e-8", "solver.threads=" + std::to_string(threads)});
    const Continuation c = continue_twice(scene, 150, 20);
    EXPECT_GT(c.saved.broken_bonds, 0);
    EXPECT_GT(c.first.broken_bonds, c.saved.broken_bonds);
    expect_repeats(c);
  }
}

TEST(SimState, DiscsInParticleContactRepeatBitForBit) {
  // saved while the discs press on each other: the Verlet list in use comes with the state
  const double dt = 1e-6;
  const SceneDef scene = parse_scene(test::discs_scene(0.01, dt, 1e-3), "discs.toml");
  const Continuation c = continue_twice(scene, 260, 120);
  ASSERT_FALSE(c.saved.contacts.empty());
  EXPECT_FALSE(c.saved.contacts[0].col.empty());
  expect_repeats(c);
}

TEST(SimState, StateOfAnotherModelIsRefused) {
  Simulation plate(load_scene(shipped("notched_plate.toml")));
  Simulation pendulum(load_scene(shipped("pendulum.toml")));
  SimState s;
  pendulum.save_state(s);
  EXPECT_THROW(plate.restore_state(s), std::invalid_argument);
}

}  // namespace
}  // namespace periflex
