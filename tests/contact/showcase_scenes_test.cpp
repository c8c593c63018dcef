// The contact showcases as shipped, run by the program as a user types it, to their end, with
// frames recorded at an interval that is no whole number of steps: scenes/hammer.toml (a
// slider-crank hammer breaks a notched beam lying on two rollers), scenes/projectile_plate.toml
// (a rigid slug through a glass pane) and scenes/plate_with_hole.toml (a plate torn apart, its
// pieces thrown back into each other). Each must end with exit 0, status ok, the exact rows and
// frames, a closed energy balance, and do what it shows: the beam broken through at mid-span,
// the slug through the pane and slowed by what it gave the glass, the torn plate's pieces
// pushing on each other without passing through.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../cli/child_run.h"
#include "../cli/run_output_files.h"
#include "../cli/run_program.h"

namespace periflex {
namespace {

using testing::ChildResult;
using testing::count_files;
using testing::fresh_directory;
using testing::read_series;
using testing::read_summary;
using testing::run_child;
using testing::scene;
using testing::Series;

// a few seconds each on a loaded two-core machine; a hang is cut off here
constexpr double kLimit = 300.0;

// Runs a shipped scene with frames every `frame_every` (when this build renders) and checks the
// run itself: exit 0, status ok, the end time reached, a row per output interval plus the end.
// `extra`: more arguments for the run; its output folder is `out_dir` when given.
Series run_showcase(const std::string& file, double end, double interval, double frame_every, long frames,
                    const std::vector<std::string>& extra = {}, std::filesystem::path* out_dir = nullptr) {
  // a folder of its own for each number of extra arguments
  std::string folder = "showcase_" + file;
  if (!extra.empty()) {
    folder += '_';
    folder += std::to_string(extra.size());
  }
  const auto out = fresh_directory(folder);
  if (out_dir) *out_dir = out;
  std::vector<std::string> args{"run", scene(file), "--out", out.string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
#ifdef PERIFLEX_TEST_RENDER
  args.insert(args.end(), {"--frames", (out / "frames").string(), "--frame-every", std::to_string(frame_every),
                           "--size", "160x96"});
#endif
  const ChildResult r = run_child(args, kLimit);
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.signal, 0) << r.output;
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto summary = read_summary(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_DOUBLE_EQ(summary["simulated_time"].get<double>(), end);
#ifdef PERIFLEX_TEST_RENDER
  EXPECT_EQ(count_files(out / "frames", ".png"), frames);
  EXPECT_EQ(summary["frames_written"], frames);
#else
  (void)frame_every;
  (void)frames;
#endif
  Series s = read_series(out / "series.csv");
  EXPECT_EQ(s.incomplete_rows, 0);
  EXPECT_EQ(static_cast<long>(s.rows.size()), std::lround(end / interval) + 1);
  return s;
}

double largest(const Series& s, const std::string& column) {
  double m = -INFINITY;
  for (const auto& row : s.rows) m = std::max(m, row[s.column(column)]);
  return m;
}

TEST(ShowcaseScenes, HammerBreaksTheNotchedBeamThroughAndTheBalanceCloses) {
  // frames every 0.3 ms over 5.9 ms: t = 0, 0.3, ..., 5.7 ms. Run past the scene's 5 ms: the crack
  // crosses the ligament by 0.8 ms, but when the halves have turned apart by another spacing depends
  // on the force loop's rounding (AVX-512: before 5 ms; AVX2: the gap is 3.4 mm at 5 ms, 4.1 mm at
  // 5.6 ms, 4.7 mm at 6 ms, still opening)
  const Series s = run_showcase("hammer.toml", 5.9e-3, 2e-5, 3e-4, 20, {"--until", "5.9e-3"});
  ASSERT_GT(s.rows.size(), 1u);
  const auto& first = s.rows.front();
  const auto& last = s.rows.back();
  const auto gap = [&](const std::vector<double>& row) {
    return std::hypot(row[s.column("probe.right_of_middle.x")] - row[s.column("probe.left_of_middle.x")],
                      row[s.column("probe.right_of_middle.y")] - row[s.column("probe.left_of_middle.y")]);
  };
  // the hammer touched the beam, and the two upper-edge particles either side of mid-span, one
  // spacing (2 mm) apart at the start, have parted by more than another spacing. In a three-point
  // bend the upper edge is squeezed while the beam holds; it opens only once the crack from the
  // notch has crossed the whole 15 mm ligament and the halves turn apart about the rollers
  EXPECT_GT(largest(s, "contact_count"), 0.0);
  EXPECT_NEAR(gap(first), 2e-3, 1e-9);
  EXPECT_GT(gap(last), 4e-3) << "the beam is not broken through";
  EXPECT_GT(last[s.column("broken_bonds")], 0.0);
  // the driver's work is all accounted for (contact forces and their damping included)
  const double work = largest(s, "driver_work");
  EXPECT_GT(work, 0.0);
  for (const auto& row : s.rows) EXPECT_LT(std::abs(row[s.column("energy_balance")]), 0.01 * work) << row[0];
}

TEST(ShowcaseScenes, ProjectileGoesThroughTheGlassPaneSlowedByWhatItGaveIt) {
  // frames every 7 us over 120 us: t = 0, 7, ..., 119 us
  const Series s = run_showcase("projectile_plate.toml", 1.2e-4, 1e-6, 7e-6, 18);
  ASSERT_GT(s.rows.size(), 1u);
  const auto& last = s.rows.back();
  const double kinetic0 = s.rows.front()[s.column("kinetic")];
  EXPECT_NEAR(kinetic0, 0.5 * 0.005 * 150.0 * 150.0, 1e-9);
  // the slug (4 mm radius) is wholly below the pane's lower face (y = -2 mm), still going down
  // but slower: the momentum it lost went into the glass
  EXPECT_LT(last[s.column("probe.slug.y")], -0.002 - 0.004);
  const double exit_speed = -last[s.column("probe.slug.vy")];
  EXPECT_GT(exit_speed, 50.0);
  EXPECT_LT(exit_speed, 0.95 * 150.0);
  EXPECT_GT(last[s.column("broken_bonds")], 0.0);
  // the energy of the shot is all accounted for: in the glass, its fracture, the contact damping
  for (const auto& row : s.rows) EXPECT_LT(std::abs(row[s.column("energy_balance")]), 1e-3 * kinetic0) << row[0];
}

// The particle positions of a VTK snapshot (OUT/vtk/particles_*.vtu, docs/running.md): the
// "position" array's UInt64 byte count and Float64 x, y, z values in the appended block.
std::vector<double> vtu_positions(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string doc = buffer.str();
  const size_t at = doc.find("Name=\"position\"");
  const size_t base = doc.find("<AppendedData encoding=\"raw\">");
  if (at == std::string::npos || base == std::string::npos) return {};
  const size_t key = doc.find("offset=\"", at) + 8;
  const size_t start = doc.find('_', base) + 1 + std::stoull(doc.substr(key, doc.find('"', key) - key));
  uint64_t bytes = 0;
  std::memcpy(&bytes, doc.data() + start, sizeof bytes);
  std::vector<double> xyz(bytes / sizeof(double));
  std::memcpy(xyz.data(), doc.data() + start + sizeof bytes, xyz.size() * sizeof(double));
  return xyz;
}

// The smallest distance between two particles over every snapshot of a run.
double closest_pair_over_run(const std::filesystem::path& out, long& snapshots) {
  double closest = INFINITY;
  snapshots = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out / "vtk")) {
    if (entry.path().extension() != ".vtu") continue;
    const std::vector<double> p = vtu_positions(entry.path());
    const size_t n = p.size() / 3;
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 1; b < n; ++b)
        closest = std::min(closest, std::hypot(p[3 * b] - p[3 * a], p[3 * b + 1] - p[3 * a + 1]));
    ++snapshots;
  }
  return closest;
}

TEST(ShowcaseScenes, PlateWithHoleTearsIntoPiecesThatCollideWithoutPassingThrough) {
  // frames every 0.3 ms over 1 ms: t = 0, 0.3, 0.6, 0.9 ms; snapshots every 70 steps
  std::filesystem::path out;
  const Series s = run_showcase("plate_with_hole.toml", 1e-3, 1e-5, 3e-4, 4, {"--vtk-every", "70"}, &out);
  ASSERT_GT(s.rows.size(), 1u);
  const auto& first = s.rows.front();
  const auto& last = s.rows.back();
  // torn: a fifth of all bonds broken, and the particles either side of the ligament above the
  // hole, a spacing (1 mm) apart at the start, more than two spacings apart at the end
  const auto gap = [&](const std::vector<double>& row) {
    return std::hypot(row[s.column("probe.above_right.x")] - row[s.column("probe.above_left.x")],
                      row[s.column("probe.above_right.y")] - row[s.column("probe.above_left.y")]);
  };
  EXPECT_NEAR(gap(first), 1e-3, 1e-9);
  EXPECT_GT(gap(last), 2e-3) << "the ligament above the hole is not torn";
  EXPECT_GT(last[s.column("mean_damage")], 0.1);
  // the pieces touched, and no two particles ever came within half a spacing: the particles
  // of one piece stay about a spacing apart (their bonds hold them), so only particles of
  // different pieces could, and contact keeps them apart
  EXPECT_GT(largest(s, "contact_count"), 0.0);
  long snapshots = 0;
  const double closest = closest_pair_over_run(out, snapshots);
  std::printf("plate with hole: closest particles %.3f mm over %ld snapshots\n", 1e3 * closest, snapshots);
  EXPECT_EQ(snapshots, 3400 / 70 + 2);  // steps 0, 70, ..., 3360 and the last, 3400
  EXPECT_GT(closest, 0.5e-3);
  // the work of the prescribed motion of the ends is all accounted for: in the plate, in its
  // fracture, in the contact (which does no net work: e = 1)
  const double work = largest(s, "driver_work");
  EXPECT_GT(work, 0.1);
  for (const auto& row : s.rows) EXPECT_LT(std::abs(row[s.column("energy_balance")]), 2e-3 * work) << row[0];
}

TEST(ShowcaseScenes, PlateWithHoleWithoutContactStiffnessLetsItsPiecesPassThrough) {
  // the check above can fail: with a contact a million times too soft the pieces run into each
  // other and particles of different pieces come far closer than half a spacing
  std::filesystem::path out;
  run_showcase("plate_with_hole.toml", 1e-3, 1e-5, 3e-4, 4,
               {"--vtk-every", "70", "--set", "contact.fragments.stiffness=1e-3"}, &out);
  long snapshots = 0;
  const double closest = closest_pair_over_run(out, snapshots);
  std::printf("plate with hole, soft contact: closest particles %.3f mm\n", 1e3 * closest);
  EXPECT_LT(closest, 0.5e-3);
}

}  // namespace
}  // namespace periflex
