// Simulation::save_state / restore_state hold everything the next step reads: N steps, save,
// M steps, restore, M steps again gives every coordinate, bond and account bit for bit, both in
// the same Simulation (bonds broken since the save heal) and in a fresh one built from the scene
// (what a restart from a checkpoint does), and from the compact state a checkpoint file holds.
// Scenes: a rigid mechanism through singular positions,
// a coupled plate that cracks, both plate models (state-based included), the glass plate (coarse
// grid, shortened) at one and two threads, and two discs in particle contact.
#include <gtest/gtest.h>

#include <cstdint>
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

// m steps of `sim`, then its state
SimState after_steps(Simulation& sim, long m) {
  for (long k = 0; k < m; ++k) sim.step();
  SimState s;
  sim.save_state(s);
  return s;
}

// a fresh Simulation of `scene` restored from `saved` (what a restart from a checkpoint does),
// m steps, then its state
SimState restored_then_stepped(const SceneDef& scene, const SimState& saved, long m) {
  Simulation other(scene);
  other.restore_state(saved);
  return after_steps(other, m);
}

// n steps, save, m steps (first), restore, m steps (again); a fresh Simulation restored from the
// save, m steps (fresh).
Continuation continue_twice(const SceneDef& scene, long n, long m) {
  Continuation c;
  Simulation sim(scene);
  for (long k = 0; k < n; ++k) sim.step();
  sim.save_state(c.saved);
  c.first = after_steps(sim, m);
  sim.restore_state(c.saved);
  c.again = after_steps(sim, m);
  c.fresh = restored_then_stepped(scene, c.saved, m);
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

// save_state_for_file: n steps, the state for a file, m steps (first); the same scene run n + m
// steps without any save (plain); a fresh Simulation restored from the state for a file, m steps
// (fresh).
struct FileContinuation {
  SimState saved, first, plain, fresh;
};

FileContinuation continue_from_file_state(const SceneDef& scene, long n, long m) {
  FileContinuation c;
  Simulation sim(scene);
  for (long k = 0; k < n; ++k) sim.step();
  sim.save_state_for_file(c.saved);
  c.first = after_steps(sim, m);
  Simulation plain(scene);
  c.plain = after_steps(plain, n + m);
  c.fresh = restored_then_stepped(scene, c.saved, m);
  return c;
}

// Share of the predicted cache's values whose bits equal the evaluation's exactly (stored as 0).
double exact_share(const SimState& s) {
  const Eigen::VectorXd& v = s.integrator.vectors.at(0);
  long zero = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    uint64_t bits;
    std::memcpy(&bits, &v[i], sizeof bits);
    zero += bits == 0;
  }
  return v.size() ? double(zero) / double(v.size()) : 0.0;
}

// The state for a file keeps velocity Verlet's end acceleration as its difference from an
// evaluation at the state (most of it zero bits): the run that saved it goes on as if nothing
// had been evaluated, and a fresh simulation restored from it repeats the run bit for bit. The
// cracking plate (the evaluation sees bonds on the verge of breaking), the glass plate at one and
// two threads, the plate with bond damping (the cache saw the half-step velocity, the evaluation
// the whole-step one, so fewer values are exact: correct all the same) and discs in contact.
TEST(SimState, StateForAFileRepeatsBitForBitAndLeavesTheRunAlone) {
  const struct {
    const char* name;
    SceneDef scene;
    long n, m;
    double exact_at_least;  // share of the cache predicted exactly
  } cases[] = {
      {"cracking plate", load_scene(shipped("notched_plate.toml")), 1700, 150, 0.9},
      {"glass plate, 1 thread",
       load_scene(shipped("glass_branching.toml"), {"flex_body.plate.grid_spacing=5e-4", "flex_body.plate.horizon_ratio=3",
                                                    "solver.dt=5e-8", "solver.threads=1"}),
       150, 20, 0.9},
      {"glass plate, 2 threads",
       load_scene(shipped("glass_branching.toml"), {"flex_body.plate.grid_spacing=5e-4", "flex_body.plate.horizon_ratio=3",
                                                    "solver.dt=5e-8", "solver.threads=2"}),
       150, 20, 0.9},
      {"damped plate", load_scene(shipped("notched_plate.toml"), {"flex_body.plate.bond_damping=2e3"}), 1200, 100, 0.0},
      {"discs in contact", parse_scene(test::discs_scene(0.01, 1e-6, 1e-3), "discs.toml"), 260, 120, 0.5},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const FileContinuation r = continue_from_file_state(c.scene, c.n, c.m);
    ASSERT_TRUE(r.saved.integrator.predicted);
    EXPECT_GE(exact_share(r.saved), c.exact_at_least);
    expect_same(r.first, r.plain, "the run that saved the state");
    expect_same(r.first, r.fresh, "restored from the state for a file");
  }
}

TEST(SimState, StateOfAnotherModelIsRefused) {
  Simulation plate(load_scene(shipped("notched_plate.toml")));
  Simulation pendulum(load_scene(shipped("pendulum.toml")));
  SimState s;
  pendulum.save_state(s);
  EXPECT_THROW(plate.restore_state(s), std::invalid_argument);
}

// Looking at a run does not change it: a simulation asked after every step for a sample, a
// full-precision snapshot and the joints' reactions (what the window, the VTK writer and the
// inspector ask) ends bit for bit where one left alone ends, through a running crack (the
// notched plate, its fracture energy lowered so that it cracks within the run) and a coupled
// mechanism with reactions to solve (the flexible slider-crank).
TEST(SimState, LookingAtTheRunLeavesItBitForBit) {
  // the plate also under the integrators whose last evaluation is not at the accepted state (bonds
  // break in symplectic Euler's evaluations, after rk4's step)
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"notched_plate.toml", {"flex_body.plate.material.fracture_energy=3"}},
      {"notched_plate.toml", {"flex_body.plate.material.fracture_energy=3", "solver.integrator=symplectic_euler"}},
      {"notched_plate.toml", {"flex_body.plate.material.fracture_energy=3", "solver.integrator=rk4"}},
      {"flexible_slider_crank.toml", {}}};
  for (const auto& [name, overrides] : runs) {
    SCOPED_TRACE(name + (overrides.size() > 1 ? " " + overrides.back() : ""));
    const SceneDef scene = load_scene(shipped(name), overrides);
    Simulation alone(scene), watched(scene);
    for (int step = 0; step < 600; ++step) {
      alone.step();
      watched.step();
      (void)watched.sample();
      Snapshot snapshot;
      snapshot.full_precision = true;
      snapshot.with_reactions = true;
      watched.fill_snapshot(snapshot);
      watched.fill_reactions(snapshot);
    }
    SimState a, b;
    alone.save_state(a);
    watched.save_state(b);
    expect_same(a, b, "watched against left alone");
    if (name == "notched_plate.toml") {
      EXPECT_GT(a.broken_bonds, 20) << "the crack did not start";
    }
  }
}

}  // namespace
}  // namespace periflex
