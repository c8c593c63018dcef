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

#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

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
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kUnderSanitizer = true;
#else
constexpr bool kUnderSanitizer = false;
#endif

TEST(SceneBudget, MemoryEstimateIsWithinOneAndAHalfOfThePeakOfTheRun) {
  if (kUnderSanitizer) GTEST_SKIP() << "peak memory under a sanitizer is not the program's";
  const std::string root = PERIFLEX_SOURCE_ROOT;
  const std::vector<MemoryCase> cases = {
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

}  // namespace
}  // namespace periflex
