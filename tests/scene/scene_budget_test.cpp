// The memory the budget expects a run to need against the peak resident memory the run really
// reaches (measured by the kernel for the child process), on shipped flexible scenes and on a
// thin sliver, whose particles sit on an edge with half an interior particle's neighbours; and
// the exact neighbour count behind it.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli/run_program.h"

#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "support/text_match.h"
#include "support/sanitizer_build.h"

namespace periflex {
namespace {

// Peak resident bytes of `periflex run` with these arguments (its own rusage, from wait4).
double peak_resident_bytes(const std::vector<std::string>& arguments) {
  std::vector<std::string> argv = {PERIFLEX_BINARY, "run"};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::fflush(stdout);  // the child must not print what this process has buffered
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> raw;
    for (auto& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    if (!std::freopen("/dev/null", "w", stdout)) _exit(126);
    execv(raw[0], raw.data());
    _exit(127);
  }
  int status = 0;
  struct rusage usage {};
  if (wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1.0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB on Linux
}

struct MemoryCase {
  std::string scene, integrator;
  double until;
  std::vector<std::string> overrides = {};
};

// Sanitizers add shadow memory and keep freed blocks in quarantine: the peak is theirs, not the
// program's.
constexpr bool kUnderSanitizer = PERIFLEX_UNDER_SANITIZER;

// A graded point file of the glass plate's size: spacing 5e-4 on its left half, 2.5e-4 (a quarter
// of the volume) on its right half, 50,000 points; and a scene reading it. Returns the scene.
std::string graded_plate_scene(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::FILE* points = std::fopen((dir / "graded.csv").c_str(), "w");
  const double dx = 5e-4, t = 1e-3;
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 100; ++i) std::fprintf(points, "%.17g,%.17g,%.17g\n", (i - 99.5) * dx, (j - 39.5) * dx, dx * dx * t);
  for (int j = 0; j < 160; ++j)
    for (int i = 0; i < 200; ++i)
      std::fprintf(points, "%.17g,%.17g,%.17g\n", (i + 0.5) * 0.5 * dx, (j - 79.5) * 0.5 * dx, 0.25 * dx * dx * t);
  std::fclose(points);
  std::FILE* scene = std::fopen((dir / "graded.toml").c_str(), "w");
  std::fprintf(scene, "[solver]\nintegrator = \"verlet\"\ndt = 2e-8\nend_time = 1e-6\n[[flex_body]]\nname = \"plate\"\n"
                      "shape = { type = \"points\", file = \"graded.csv\" }\ngrid_spacing = 5e-4\nthickness = 1e-3\n"
                      "[flex_body.material]\nyoungs_modulus = 72e9\ndensity = 2440\nfracture_energy = 3.8\n");
  std::fclose(scene);
  return (dir / "graded.toml").string();
}

TEST(SceneBudget, MemoryEstimateIsWithinOneAndAHalfOfThePeakOfTheRun) {
  if (kUnderSanitizer) GTEST_SKIP() << "peak memory under a sanitizer is not the program's";
  const std::string root = PERIFLEX_SOURCE_ROOT;
  const std::string graded =
      graded_plate_scene(std::filesystem::temp_directory_path() / ("periflex_budget_graded_" + std::to_string(::getpid())));
  const std::vector<MemoryCase> cases = {
      // bodies off the grid: each bond keeps its own length and partial volume
      {root + "/scenes/glass_branching.toml", "verlet", 2e-7, {"flex_body.plate.jitter=0.3"}},
      {graded, "verlet", 1e-7},
      {root + "/scenes/notched_plate.toml", "verlet", 4e-6},
      {root + "/scenes/notched_plate.toml", "hht", 4e-6},
      // steps of 3e-6 s cut at every output (1e-5 s): the matrices of two step sizes
      {root + "/scenes/notched_plate.toml", "hht", 5e-5, {"solver.dt=3e-6"}},
      {root + "/scenes/glass_branching.toml", "verlet", 2e-7},
      {root + "/scenes/flexible_pendulum.toml", "verlet", 1e-3},
      {root + "/tests/data/scenes/thin_sliver.toml", "verlet", 1e-7},
      {root + "/tests/data/scenes/thin_sliver.toml", "rk4", 3e-8},
  };
  const auto dir = std::filesystem::temp_directory_path() / ("periflex_budget_memory_" + std::to_string(::getpid()));
  for (const MemoryCase& c : cases) {
    std::filesystem::remove_all(dir);
    std::vector<std::string> sets = c.overrides;
    sets.push_back("solver.integrator=" + c.integrator);
    const SceneBudget budget = check_scene_budget(load_scene(c.scene, sets));
    char until[32];
    std::snprintf(until, sizeof until, "%.17g", c.until);
    std::vector<std::string> args = {c.scene};
    for (const std::string& set : sets) args.insert(args.end(), {"--set", set});
    args.insert(args.end(), {"--until", until, "--out", dir.string(), "--quiet"});
    const double peak = peak_resident_bytes(args);
    ASSERT_GT(peak, 0.0) << c.scene << " did not run";
    const double ratio = budget.memory / peak;
    std::printf("%s (%s): estimate %.1f MB, peak %.1f MB, ratio %.2f\n",
                std::filesystem::path(c.scene).filename().c_str(), c.integrator.c_str(), budget.memory / 1e6,
                peak / 1e6, ratio);
    EXPECT_LT(ratio, 1.5) << c.scene << " " << c.integrator;
    EXPECT_GT(ratio, 1.0 / 1.5) << c.scene << " " << c.integrator;
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneBudget, BondCountIsExactOnASliverAndAPlate) {
  // the bonds the model builds against the budget's count (before any notch or hole cuts one)
  for (const std::string scene : {"/tests/data/scenes/thin_sliver.toml", "/scenes/stability/pd_block.toml"}) {
    const SceneDef def = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + scene);
    const SceneBudget budget = check_scene_budget(def);
    Simulation sim(def);
    EXPECT_EQ(budget.particles, static_cast<double>(sim.info().particles)) << scene;
    EXPECT_EQ(budget.bonds, static_cast<double>(sim.info().bonds)) << scene;
  }
}

// The count in "series.csv would get N rows, more than limits.max_output_rows = M", or -1.
long refused_rows(const std::string& output) {
  const auto m = testing::first_match(
      output, "series\\.csv would get ([0-9]+) rows, more than limits\\.max_output_rows = ([0-9]+);");
  return m.empty() ? -1 : std::stol(m[1]);
}

// The report's case: the pendulum to 10000 s, a row every 0.01 s, writes rows at 0, 0.01, ...,
// 10000: 1000001 of them, one more than the default limit, and the message says exactly that.
TEST(SceneBudget, RowRefusalPrintsExactWholeCounts) {
  const auto out = testing::fresh_directory("budget_rows_million");
  const auto r = testing::run_periflex("run " + testing::scene("pendulum.toml") + " --until 10000 --quiet --out " +
                                       out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("series.csv would get 1000001 rows, more than limits.max_output_rows = 1000000"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("e+0"), std::string::npos) << r.output;
}

// The count a refusal prints is the count the run writes: the limit set to it, the run goes
// through and its series.csv holds that many rows; one less, and it is refused. dt = 3 ms does
// not divide the output interval (7 ms) nor the end (0.1 s): rows at 0, 7, ..., 98 ms and the end.
TEST(SceneBudget, RowCountOfTheRefusalIsTheCountTheRunWrites) {
  const auto out = testing::fresh_directory("budget_rows_exact");
  const std::string run = "run " + testing::scene("pendulum.toml") +
                          " --until 0.1 --dt 3e-3 --set solver.output_interval=7e-3 --quiet --out " + out.string();
  const auto small = testing::run_periflex(run + " --set limits.max_output_rows=5");
  ASSERT_EQ(small.exit_code, 2) << small.output;
  const long count = refused_rows(small.output);
  ASSERT_GT(count, 5) << small.output;
  EXPECT_EQ(count, static_cast<long>(std::floor(0.1 / 7e-3)) + 2);
  const auto fits = testing::run_periflex(run + " --set limits.max_output_rows=" + std::to_string(count));
  ASSERT_EQ(fits.exit_code, 0) << fits.output;
  const std::string series = testing::read_text(out / "series.csv");
  EXPECT_EQ(static_cast<long>(std::count(series.begin(), series.end(), '\n')) - 1, count);
  const auto short_by_one = testing::run_periflex(run + " --set limits.max_output_rows=" + std::to_string(count - 1));
  EXPECT_EQ(short_by_one.exit_code, 2) << short_by_one.output;
  EXPECT_EQ(refused_rows(short_by_one.output), count) << short_by_one.output;
}

}  // namespace
}  // namespace periflex
