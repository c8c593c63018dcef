// `periflex run` on the GPU as typed, beyond the flag: solver.device and solver.precision in the
// scene (the flag overriding the key, values out of their choices refused), the same rows from two
// runs of one scene, and checkpoints written on one device continued on the other.
#include <gtest/gtest.h>

#include <csignal>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "../cli/child_run.h"
#include "gpu_program_support.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

// The notched plate with its crack started early (fracture energy a hundredth), to 1.2e-4 s.
const std::string& cracking_plate() {
  static const std::string args =
      scene("notched_plate.toml") + " --quiet --until 1.2e-4 --set flex_body.plate.material.fracture_energy=3";
  return args;
}

// solver.device = "gpu" given as a key runs the forces on the GPU; --device cpu overrides it.
TEST(GpuRun, SceneKeyChoosesTheGpuAndTheFlagOverridesIt) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("gpu_key");
  const std::string common = scene("notched_plate.toml") + " --quiet --until 1e-5 --set solver.device=gpu" +
                             " --set solver.precision=fp32";
  const ProgramResult key = run_periflex("run " + common + " --out " + (dir / "key").string());
  ASSERT_EQ(key.exit_code, 0) << key.output;
  const std::string summary = read_text(dir / "key" / "summary.json");
  EXPECT_NE(summary.find("\"device\": \"gpu\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"precision\": \"fp32\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("OpenGL compute fp32"), std::string::npos) << summary;
  const ProgramResult flag = run_periflex("run " + common + " --device cpu --out " + (dir / "flag").string());
  ASSERT_EQ(flag.exit_code, 0) << flag.output;
  const std::string cpu_summary = read_text(dir / "flag" / "summary.json");
  EXPECT_NE(cpu_summary.find("\"device\": \"cpu\""), std::string::npos) << cpu_summary;
  // the CPU computes in fp64 whatever the key says for the GPU
  EXPECT_NE(cpu_summary.find("\"precision\": \"fp64\""), std::string::npos) << cpu_summary;
}

// Values out of the keys' choices: exit 2 naming the key and what it takes, before any row.
TEST(GpuRun, KeysOutOfTheirChoicesAreRefused) {
  for (const std::string set : {"solver.precision=fp16", "solver.device=tpu"}) {
    const fs::path out = fresh_directory("gpu_bad_key");
    const ProgramResult r = run_periflex("run " + scene("notched_plate.toml") + " --quiet --set " + set +
                                         " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << set << ": " << r.output;
    EXPECT_NE(r.output.find(set.substr(0, set.find('='))), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(set.find("precision") != std::string::npos ? "fp32" : "gpu"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out / "series.csv"));
  }
}

// A law the GPU does not run, chosen for the GPU by the scene's key: the refusal names the key.
TEST(GpuRun, RefusalNamesTheKeyThatChoseTheGpu) {
  const ProgramResult r = run_periflex("run " + scene("notched_plate_models.toml") +
                                       " --quiet --set solver.device=gpu --out " +
                                       fresh_directory("gpu_key_law").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("solver.device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bond_based"), std::string::npos) << r.output;
}

// Two runs of the same scene on the GPU, in each precision, write the same rows bit for bit: each
// row's sum is gathered by one invocation in a fixed order and nothing is summed by atomics.
TEST(GpuRun, TwoRunsWriteTheSameRows) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("gpu_twice");
  for (const std::string precision : {"fp64", "fp32"}) {
    std::vector<Series> runs;
    for (const std::string name : {"a", "b"}) {
      const fs::path out = dir / (precision + name);
      const ProgramResult r = run_periflex("run " + cracking_plate() + " --device gpu --set solver.precision=" +
                                           precision + " --out " + out.string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
      runs.push_back(read_series(out / "series.csv"));
    }
    ASSERT_GT(runs[0].rows.size(), 5u);
    EXPECT_GT(runs[0].rows.back()[runs[0].column("broken_bonds")], 20.0) << "the crack did not start";
    EXPECT_TRUE(same_rows(runs[0], runs[1])) << precision;
  }
}

// A checkpoint written on one device, continued on the other: the rows from the checkpoint on are
// those of the run that went on where it started, broken bonds exactly and the other columns within
// 1e-6 of their largest value (the two paths sum each row's bonds in another order; see
// DeviceOption.NotchedPlateOnTheGpuWritesTheCpuRows).
TEST(GpuRun, CheckpointsContinueOnTheOtherDevice) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("gpu_checkpoint");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"gpu", "cpu"}, {"cpu", "gpu"}}) {
    const fs::path whole = dir / (from + "_whole"), continued = dir / (from + "_to_" + to);
    const ProgramResult a = run_periflex("run " + cracking_plate() + " --device " + from + " --checkpoint-every 5e-5" +
                                         " --out " + whole.string());
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const auto files = files_with_extension(whole / "checkpoints", ".pfstate");
    ASSERT_GE(files.size(), 1u) << a.output;
    const ProgramResult b = run_periflex("run " + cracking_plate() + " --device " + to + " --restart " +
                                         files[0].string() + " --out " + continued.string());
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const Series s = read_series(whole / "series.csv"), c = read_series(continued / "series.csv");
    ASSERT_EQ(s.columns, c.columns);
    ASSERT_GE(c.rows.size(), 3u);
    ASSERT_LE(c.rows.size(), s.rows.size());
    const size_t offset = s.rows.size() - c.rows.size();
    const int broken = s.column("broken_bonds"), speed = s.find_column("steps_per_second");
    EXPECT_GT(s.rows.back()[broken], 20.0) << "the crack did not start";
    for (size_t col = 0; col < s.columns.size(); ++col) {
      if (static_cast<int>(col) == speed) continue;
      double largest = 0.0;
      for (const auto& row : s.rows) largest = std::max(largest, std::abs(row[col]));
      for (size_t r = 0; r < c.rows.size(); ++r) {
        const double expected = s.rows[offset + r][col], got = c.rows[r][col];
        if (static_cast<int>(col) == broken)
          EXPECT_EQ(got, expected) << from << " to " << to << ", row " << r;
        else
          EXPECT_LE(std::abs(got - expected), 1e-6 * largest) << from << " to " << to << ", " << s.columns[col];
      }
    }
  }
}

// Whether every row of a series is whole and finite, its times rising.
void expect_valid_rows(const Series& s, const std::string& what) {
  EXPECT_EQ(s.incomplete_rows, 0) << what;
  for (size_t r = 0; r < s.rows.size(); ++r) {
    for (double value : s.rows[r]) EXPECT_TRUE(std::isfinite(value)) << what << ", row " << r;
    if (r > 0) {
      EXPECT_GT(s.rows[r][0], s.rows[r - 1][0]) << what << ", row " << r;
    }
  }
}

// The GPU's context lost part-way (a preloaded stand-in answers GL_CONTEXT_LOST after 150 passes,
// about step 150 of 300): exit 3 naming the GPU's failure, the rows before it whole, summary.json
// saying what happened and where the run stopped.
TEST(GpuRun, LostContextStopsWithExit3AndValidOutputs) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path out = fresh_directory("gpu_lost");
  const ProgramResult r =
      run_periflex_with(std::string("LD_PRELOAD=") + PERIFLEX_GL_FAULT_SHIM + " PERIFLEX_TEST_GL_LOST_AFTER=150",
                        "run " + cracking_plate() + " --device gpu --out " + out.string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("GPU failure"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("context was lost"), std::string::npos) << r.output;
  const Series s = read_series(out / "series.csv");
  expect_valid_rows(s, "lost context");
  ASSERT_GE(s.rows.size(), 3u);
  EXPECT_LT(s.rows.back()[0], 1.2e-4);
  const auto summary = read_summary(out / "summary.json");
  EXPECT_EQ(summary["exit_code"], 3);
  EXPECT_EQ(summary["status"], "device_failure");
  EXPECT_EQ(summary["device"], "gpu");
  // the time of the last whole step, at or after the last row and before the end
  EXPECT_GE(summary["simulated_time"].get<double>(), s.rows.back()[0]);
  EXPECT_LT(summary["simulated_time"].get<double>(), 1.2e-4);
}

// Ctrl-C while the GPU runs: the run stops cleanly (exit 130) with whole rows and a summary.
TEST(GpuRun, InterruptedRunLeavesValidOutputs) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path out = fresh_directory("gpu_interrupt");
  Child child({"run", scene("notched_plate.toml"), "--quiet", "--device", "gpu", "--out", out.string()});
  ASSERT_TRUE(child.started());
  child.wait_until([&] { return read_series(out / "series.csv").rows.size() >= 4; }, 60);
  child.send(SIGINT);
  const ChildResult result = child.finish(60);
  EXPECT_EQ(result.exit_code, 130) << result.output;
  const Series s = read_series(out / "series.csv");
  expect_valid_rows(s, "interrupted");
  ASSERT_GE(s.rows.size(), 4u);
  const auto summary = read_summary(out / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["device"], "gpu");
}

// `periflex check` says whether the GPU path could run the scene here, and why not.
TEST(GpuRun, CheckSaysWhetherTheGpuPathRunsHere) {
  const ProgramResult law = run_periflex("check " + scene("notched_plate_models.toml"));
  EXPECT_NE(law.output.find("not for this scene: flexible body"), std::string::npos) << law.output;
  const ProgramResult no_egl =
      run_periflex_with("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json", "check " + scene("notched_plate.toml"));
  EXPECT_EQ(no_egl.exit_code, 0) << no_egl.output;
  EXPECT_NE(no_egl.output.find("the GPU path (fp64): not here: "), std::string::npos) << no_egl.output;
  EXPECT_NE(no_egl.output.find("EGL"), std::string::npos) << no_egl.output;
  if (!compute_unavailable().empty()) return;
  const ProgramResult here = run_periflex("check " + scene("notched_plate.toml") + " --set solver.precision=fp32");
  EXPECT_EQ(here.exit_code, 0) << here.output;
  EXPECT_NE(here.output.find("the GPU path (fp32): available, OpenGL compute fp32"), std::string::npos) << here.output;
}

// `periflex sweep --device gpu`: every run of the sweep runs its forces on the GPU.
TEST(GpuRun, SweepPassesTheDeviceToEveryRun) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("gpu_sweep");
  {
    std::ofstream file(dir / "sweep.toml");
    file << "[sweep]\nscene = \"" << scene("notched_plate.toml") << "\"\nset = [\"solver.end_time=8e-6\"]\n"
         << "jobs = 1\n\n[[parameter]]\nkey = \"flex_body.plate.material.fracture_energy\"\nvalues = [150.0, 300.0]\n";
  }
  const ProgramResult r = run_periflex("sweep " + (dir / "sweep.toml").string() + " --quiet --device gpu --out " +
                                       (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int runs = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out")) {
    if (entry.path().filename() != "summary.json") continue;
    EXPECT_EQ(read_summary(entry.path())["device"], "gpu") << entry.path();
    ++runs;
  }
  EXPECT_EQ(runs, 2);
}

// A GPU with too little memory free for the scene's bonds (its driver's answer stood in for by a
// preloaded library, as NVIDIA's GL_NVX_gpu_memory_info gives it): refused before the run, exit 2
// naming --device, what the scene needs and what is free; with room enough it runs.
TEST(GpuRun, RefusesAScenePastTheGpusFreeMemory) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("gpu_memory");
  const std::string run = "run " + scene("notched_plate.toml") + " --quiet --until 1e-5 --device gpu --out ";
  const std::string shim = std::string("LD_PRELOAD=") + PERIFLEX_GL_FAULT_SHIM;
  // the notched plate's 4,000 particles and 136k bond directions hold about 1.5 MB
  const ProgramResult small = run_periflex_with(shim + " PERIFLEX_TEST_GPU_FREE_KB=1000", run + (dir / "small").string());
  EXPECT_EQ(small.exit_code, 2) << small.output;
  EXPECT_NE(small.output.find("--device"), std::string::npos) << small.output;
  EXPECT_NE(small.output.find("MB of GPU memory"), std::string::npos) << small.output;
  EXPECT_NE(small.output.find("1.02 MB free"), std::string::npos) << small.output;
  EXPECT_FALSE(fs::exists(dir / "small" / "series.csv"));
  const ProgramResult room = run_periflex_with(shim + " PERIFLEX_TEST_GPU_FREE_KB=4000", run + (dir / "room").string());
  EXPECT_EQ(room.exit_code, 0) << room.output;
}

}  // namespace
}  // namespace periflex::testing
