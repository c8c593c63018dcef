// Peridynamic bodies inside the full Simulation (scene text -> loader -> system -> integrator):
// the energies the body reports (strain energy, dissipation, external power, fracture energy)
// must close the run's energy balance.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

// A glass strip 20 mm x 6 mm pulled at both short edges by a traction that rises over 10 us;
// bond and global damping on; a notch in the middle so the strip tears.
const char* kStripScene = R"(
[scene]
name = "strip"
gravity = [0.0, 0.0]

[solver]
integrator = "verlet"
dt = 4.0e-8
end_time = 3.0e-5
output_interval = 1.0e-6

[[flex_body]]
name = "strip"
shape = { type = "box", center = [0.0, 0.0], width = 0.02, height = 0.006 }
grid_spacing = 5.0e-4
thickness = 1.0e-3
bond_damping = 20.0
global_damping = 2000.0
notches = [ { p1 = [0.0, -0.0031], p2 = [0.0, -0.0015] } ]

[flex_body.material]
youngs_modulus = 72.0e9
density = 2440.0
fracture_energy = 3.8

[[flex_body.load]]
name = "right"
type = "traction"
region = { type = "box", center = [0.00975, 0.0], width = 0.0005, height = 0.006 }
fx = { type = "table", times = [0.0, 1.0e-5], values = [0.0, 1.5e7] }

[[flex_body.load]]
name = "left"
type = "traction"
region = { type = "box", center = [-0.00975, 0.0], width = 0.0005, height = 0.006 }
fx = { type = "table", times = [0.0, 1.0e-5], values = [0.0, -1.5e7] }
)";

TEST(PdSimulation, EnergyBalanceClosesWithTractionDampingAndFracture) {
  Simulation sim(parse_scene(kStripScene, "strip.toml"));
  sim.initialize();
  EXPECT_GT(sim.info().critical_time_step, 4.0e-8);
  while (sim.time() < sim.end_time()) sim.step();
  const Sample s = sim.sample();
  std::printf("external work %.4e J, kinetic %.4e, strain %.4e, dissipated %.4e, fracture %.4e, balance %.3e; "
              "%ld bonds broken\n",
              s.energies.external_work, s.energies.kinetic, s.energies.potential_elastic, s.energies.dissipated,
              s.energies.fracture, s.energies.balance, s.broken_bonds);
  EXPECT_GT(s.broken_bonds, 0);
  EXPECT_GT(s.energies.fracture, 0.0);
  EXPECT_GT(s.energies.dissipated, 0.0);
  // every joule fed in is accounted for; 1% of the external work: the time quadrature of the
  // power terms (first order in dt across the step in which a bond breaks)
  EXPECT_LT(std::abs(s.energies.balance), 0.01 * s.energies.external_work);
}

}  // namespace
}  // namespace periflex
