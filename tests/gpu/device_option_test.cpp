// `periflex run --device gpu` as typed (cli/device_option.h): the notched plate on the GPU writes
// the same rows as on the CPU to round-off, with the same bonds broken; the refusals exit 2 naming
// --device and what is missing: a law the GPU does not run, no EGL at all, an OpenGL below 4.3.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "gpu_program_support.h"
#include "core/resources.h"
#include "gpu/gl_compute_context.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

// The notched plate with its crack started early (fracture energy a hundredth) to 1.2e-4 s, 300
// steps, by the program as typed on each path: the same rows, the same broken bonds in every row,
// and every other column equal to 1e-6 of its largest value over the run. Why 1e-6: the paths sum
// each row's bonds in another order (1e-15 of a force), which the crack's own instability grows
// over 300 steps; a wrong force or a missed break moves the columns by far more.
TEST(DeviceOption, NotchedPlateOnTheGpuWritesTheCpuRows) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  const fs::path dir = fresh_directory("device_gpu");
  const std::string common = scene("notched_plate.toml") + " --quiet --until 1.2e-4 --set flex_body.plate.material.fracture_energy=3";
  const ProgramResult cpu = run_periflex("run " + common + " --device cpu --out " + (dir / "cpu").string());
  ASSERT_EQ(cpu.exit_code, 0) << cpu.output;
  const ProgramResult gpu = run_periflex("run " + common + " --device gpu --out " + (dir / "gpu").string());
  ASSERT_EQ(gpu.exit_code, 0) << gpu.output;
  // summary.json says where the forces ran, and on what
  const std::string cpu_summary = read_text(dir / "cpu" / "summary.json"), gpu_summary = read_text(dir / "gpu" / "summary.json");
  EXPECT_NE(cpu_summary.find("\"device\": \"cpu\""), std::string::npos) << cpu_summary;
  EXPECT_NE(gpu_summary.find("\"device\": \"gpu\""), std::string::npos) << gpu_summary;
  EXPECT_NE(gpu_summary.find("renderer: "), std::string::npos) << gpu_summary;
  const Series a = read_series(dir / "cpu" / "series.csv"), b = read_series(dir / "gpu" / "series.csv");
  ASSERT_EQ(a.columns, b.columns);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_GT(a.rows.size(), 5u);
  const int broken = a.column("broken_bonds");
  ASSERT_GE(broken, 0);
  EXPECT_GT(a.rows.back()[broken], 20.0) << "the crack did not start within the run";
  for (size_t c = 0; c < a.columns.size(); ++c) {
    if (a.columns[c] == "steps_per_second") continue;  // the machine's speed, not the physics
    double largest = 0.0;
    for (const auto& row : a.rows) largest = std::max(largest, std::abs(row[c]));
    for (size_t r = 0; r < a.rows.size(); ++r) {
      if (static_cast<int>(c) == broken) {
        EXPECT_EQ(b.rows[r][c], a.rows[r][c]) << "row " << r;
      } else {
        EXPECT_LE(std::abs(b.rows[r][c] - a.rows[r][c]), 1e-6 * largest) << a.columns[c] << ", row " << r;
      }
    }
  }
}

// A scene with a body whose law runs only on the CPU: refused before anything runs.
TEST(DeviceOption, RefusesALawTheGpuDoesNotRun) {
  const ProgramResult r = run_periflex("run " + scene("notched_plate_models.toml") + " --quiet --device gpu --out " +
                                       fresh_directory("device_law").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bond_based"), std::string::npos) << r.output;
}

// A body whose particles lie off the grid (its bonds keep their own lengths, which the GPU's
// length classes cannot hold): refused before anything runs, naming the body and why.
TEST(DeviceOption, RefusesABodyOffTheGrid) {
  const fs::path out = fresh_directory("device_off_grid");
  const ProgramResult r = run_periflex("run " + scene("notched_plate.toml") + " --quiet --device gpu" +
                                       " --set flex_body.plate.jitter=0.2 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'plate' has particles off the grid"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "series.csv"));
}

// `periflex run ... --device gpu` with `environment` before it in the shell.
ProgramResult run_gpu_with(const std::string& environment, const fs::path& out) {
  return run_periflex_with(environment, "run " + scene("notched_plate.toml") + " --quiet --until 1e-5 --device gpu --out " +
                                            out.string());
}

// No EGL driver at all (glvnd's vendor file pointed at nothing): exit 2 naming what is missing,
// before any row is written.
TEST(DeviceOption, RefusesWithoutEgl) {
  const fs::path out = fresh_directory("device_no_egl");
  const ProgramResult r = run_gpu_with("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json", out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("EGL"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "series.csv"));
}

// An OpenGL below 4.3 (Mesa told to offer 4.2 at most): no compute shaders, refused saying so.
TEST(DeviceOption, RefusesOpenGlBelowCompute) {
  REQUIRE_PROGRAM_COMPUTE_CONTEXT();
  {
    GlComputeContext probe(find_resource_root());
    if (probe.description().find("Mesa") == std::string::npos)
      GTEST_SKIP() << "the version override is Mesa's; this driver is " << probe.description();
  }
  const fs::path out = fresh_directory("device_gl42");
  const ProgramResult r = run_gpu_with("MESA_GL_VERSION_OVERRIDE=4.2", out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("OpenGL 4.3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "series.csv"));
}

}  // namespace
}  // namespace periflex::testing
