// Contact with a driven, massless (virtual) rigid body, as a user runs it: a ram held by three
// drivers strikes a free PD block (20 x 10 mm) at V = 2 m/s. A striker that cannot slow down is
// the M -> infinity limit of the strip impact: the block takes momentum 2 m V and leaves at 2 V
// after 2 L / c0 = 0.13 ms. Checked: the block's far end moves on at 2 V (within 5%: the block
// still vibrates, and the coarse 20 x 10 grid makes it a few percent stiffer than the 1D bar),
// the drivers' work is the block's kinetic energy 2 m V^2 (within 5%) and the balance closes
// (within 1% of that work), and the ram's face never sinks a third of a spacing into the block.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "../cli/run_program.h"
#include "contact_scenes.h"

namespace periflex {
namespace {

using testing::fresh_directory;
using testing::read_text;
using testing::run_periflex;

const char* kRamScene = R"([scene]
name = "ram"
gravity = [0, 0]
[solver]
integrator = "verlet"
dt = 1.3e-6
end_time = 3e-3
output_interval = 5e-6
[[body]]
name = "ram"
virtual = true
mass = 0
inertia = 0
position = [-0.005001, 0]
shape = { type = "box", width = 0.01, height = 0.02 }
[[driver]]
name = "push"
type = "absolute_position"
body_i = "ram"
function = { type = "rate", value = -0.005001, rate = 2.0 }
[[driver]]
name = "level"
type = "absolute_position"
body_i = "ram"
axis = [0, 1]
function = 0
[[driver]]
name = "square"
type = "absolute_angle"
body_i = "ram"
function = 0
[[flex_body]]
name = "block"
shape = { type = "box", center = [0.01, 0], width = 0.02, height = 0.01 }
grid_spacing = 0.001
thickness = 0.01
fracture = false
[flex_body.material]
youngs_modulus = 1e8
density = 1000
[[probe]]
name = "far"
body = "block"
point = [0.0195, 0]
[[probe]]
name = "near"
body = "block"
point = [0.0005, 0]
[[contact]]
name = "push"
type = "rigid_particles"
body = "ram"
flex_body = "block"
)";

TEST(DrivenContact, VirtualRamCarriesABlockWithoutSinkingIntoItAndTheBalanceCloses) {
  const auto dir = fresh_directory("contact_ram");
  const std::string path = test::write_scene(dir, "ram.toml", kRamScene);
  const auto run = run_periflex("run " + path + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  std::istringstream series(read_text(dir / "out" / "series.csv"));
  std::string header, line;
  std::getline(series, header);
  std::vector<std::string> names;
  {
    std::istringstream cells(header);
    std::string cell;
    while (std::getline(cells, cell, ',')) names.push_back(cell);
  }
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  std::vector<double> last;
  double deepest = 0.0, most_contacts = 0.0, far_at_1ms = 0.0;
  while (std::getline(series, line)) {
    std::vector<double> values;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) values.push_back(std::stod(cell));
    // the ram's face is at 2 t m; the nearest particle's centre half a spacing ahead of it at rest
    const double face = 2.0 * values[column("t")];
    deepest = std::max(deepest, face + 0.0005 - values.at(column("probe.near.x")));
    most_contacts = std::max(most_contacts, values.at(column("contact_count")));
    if (std::abs(values[column("t")] - 1e-3) < 1e-9) far_at_1ms = values.at(column("probe.far.x"));
    last = values;
  }
  ASSERT_FALSE(last.empty());
  EXPECT_GE(most_contacts, 10.0);  // the whole face of 10 particles
  // penetration below a third of a spacing all along
  EXPECT_LT(deepest, 0.33e-3);
  // the block has left the ram at twice its speed: the far end's mean velocity over the last 2 ms
  EXPECT_EQ(last.at(column("contact_count")), 0.0);
  const double speed = (last.at(column("probe.far.x")) - far_at_1ms) / 2e-3;
  EXPECT_NEAR(speed / 4.0, 1.0, 0.05) << speed;
  // the drivers' work is the block's energy, 2 m V^2 with m = 2 g
  const double work = last.at(column("driver_work"));
  EXPECT_NEAR(work / (2.0 * 2e-3 * 4.0), 1.0, 0.05) << work;
  EXPECT_LT(std::abs(last.at(column("energy_balance"))), 0.01 * work);
}

}  // namespace
}  // namespace periflex
