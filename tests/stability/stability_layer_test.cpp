// The stability suite's own machinery: child processes with limits, output checks, the catalogue.
// These tests need no solver: they run /bin/sh and read hand-written output files.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/resources.h"
#include "io/child_process.h"
#include "stability/run_outputs.h"
#include "stability/stability_case.h"

namespace periflex {
namespace {

ChildResult shell(const std::string& script, double timeout = 10.0) {
  ChildLimits limits;
  limits.timeout_seconds = timeout;
  return run_child({"/bin/sh", "-c", script}, limits);
}

TEST(ChildProcess, ReportsExitCodeAndCapturesBothStreams) {
  const auto r = shell("echo to-out; echo to-err >&2; exit 3");
  EXPECT_TRUE(r.started);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.signal, 0);
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.output.find("to-out"), std::string::npos);
  EXPECT_NE(r.output.find("to-err"), std::string::npos);
}

TEST(ChildProcess, ReportsACrashAsItsSignal) {
  const auto r = shell("kill -SEGV $$");
  EXPECT_EQ(r.signal, SIGSEGV);
  EXPECT_FALSE(r.timed_out);
}

TEST(ChildProcess, KillsAHangAfterItsLimitIncludingItsChildren) {
  // the grandchild keeps the pipe open: the whole process group must go
  const auto r = shell("sleep 60 & sleep 60", 0.5);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.signal, SIGKILL);
  EXPECT_LT(r.wall_seconds, 5.0);  // the limit is 0.5 s; 5 s allows for a loaded machine
}

TEST(ChildProcess, PassesExtraEnvironment) {
  ChildLimits limits;
  limits.environment = {"OMP_NUM_THREADS=7", "PERIFLEX_STABILITY_PROBE=yes"};
  const auto r = run_child({"/bin/sh", "-c", "echo $OMP_NUM_THREADS $PERIFLEX_STABILITY_PROBE"}, limits);
  EXPECT_NE(r.output.find("7 yes"), std::string::npos) << r.output;
}

TEST(ChildProcess, MemoryLimitMakesAHugeAllocationFail) {
  // 'head -c' of 2 GB into a shell variable needs more than the 200 MB allowed
  ChildLimits limits;
  limits.memory_bytes = 2e8;
  const auto r = run_child({"/bin/sh", "-c", "x=$(head -c 2000000000 /dev/zero | tr '\\0' a); echo survived"},
                           limits);
  EXPECT_EQ(r.output.find("survived\n"), std::string::npos) << r.output.substr(0, 200);
}

TEST(ChildProcess, MissingProgramIsNotStarted) {
  const auto r = run_child({"/nonexistent/program"}, ChildLimits{});
  EXPECT_FALSE(r.started);
}

TEST(SeriesParsing, RejectsNonFiniteCellsShortRowsAndACutLastRow) {
  std::vector<std::string> problems;
  const Series s = parse_series("t,a\n0,1\n0.1,nan\n0.2\n0.3,inf\n0.4,2", problems);
  EXPECT_EQ(s.rows.size(), 2u);  // rows 0 and 0.4 parse
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_NE(problems[0].find("nan"), std::string::npos);
  EXPECT_NE(problems[1].find("1 cells"), std::string::npos);
  EXPECT_NE(problems[2].find("inf"), std::string::npos);
  EXPECT_NE(problems[3].find("complete row"), std::string::npos);
}

// Writes a run directory with the given series rows and summary.
std::string write_run(const std::string& name, const std::string& series, const std::string& summary) {
  const auto dir = std::filesystem::current_path() / ("stability_layer_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "series.csv") << series;
  if (!summary.empty()) std::ofstream(dir / "summary.json") << summary;
  return dir.string();
}

const char* kHeader =
    "t,kinetic,potential_gravity,potential_elastic,dissipated,fracture,external_work,driver_work,energy_balance,"
    "violation_position,violation_velocity\n";

TEST(RunOutputs, MeasuresEnergyErrorViolationAndDriftSlopes) {
  // balance = 1e-3 t and violation = 2e-6 t exactly: the least-squares slopes are those numbers
  std::string rows = kHeader;
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    char line[256];
    std::snprintf(line, sizeof line, "%g,%g,%g,0,0,0,0,0,%g,%g,0\n", t, 2.0 * t, -2.0 * t, 1e-3 * t, 2e-6 * t);
    rows += line;
  }
  const auto dir = write_run("measures", rows, R"({"status":"ok","exit_code":0,"steps":100,"message":""})");
  const RunOutputs out = read_run_outputs(dir, 0);
  EXPECT_TRUE(out.valid) << (out.problems.empty() ? "" : out.problems.front());
  EXPECT_EQ(out.rows, 11);
  EXPECT_NEAR(out.energy_error, 1e-3, 1e-15);
  EXPECT_NEAR(out.energy_scale, 2.0, 1e-15);  // kinetic and |gravity change| both reach 2
  EXPECT_NEAR(out.relative_energy_error(), 5e-4, 1e-15);
  EXPECT_NEAR(out.max_violation, 2e-6, 1e-18);
  EXPECT_NEAR(out.energy_drift_rate, 1e-3, 1e-12);
  EXPECT_NEAR(out.violation_drift_rate, 2e-6, 1e-15);
}

TEST(RunOutputs, StatusMustAgreeWithTheExitCode) {
  const std::string rows = std::string(kHeader) + "0,0,0,0,0,0,0,0,0,0,0\n";
  const auto ok_dir = write_run("status", rows, R"({"status":"ok","exit_code":0,"message":""})");
  EXPECT_FALSE(read_run_outputs(ok_dir, 3).valid);  // exit 3 needs numerical_failure
  const auto failed = write_run("failed", rows, R"({"status":"numerical_failure","exit_code":3,"message":"x"})");
  EXPECT_TRUE(read_run_outputs(failed, 3).valid);
  const auto silent = write_run("silent", rows, R"({"status":"numerical_failure","exit_code":3,"message":""})");
  EXPECT_FALSE(read_run_outputs(silent, 3).valid);  // a failure must say what failed
  const auto broken = write_run("broken", rows, R"({"status":"ok", "exit_code":)");
  EXPECT_FALSE(read_run_outputs(broken, 0).valid);
  const auto missing = write_run("missing", rows, "");
  EXPECT_FALSE(read_run_outputs(missing, 0).valid);
}

TEST(RunOutputs, ASuccessfulRunNeedsRows) {
  const auto dir = write_run("norows", kHeader, R"({"status":"ok","exit_code":0,"message":""})");
  EXPECT_FALSE(read_run_outputs(dir, 0).valid);
}

TEST(Catalogue, NamesAreUniqueScenesExistAndExpectationsAreStated) {
  const auto cases = stability_cases();
  std::set<std::string> names;
  int quick = 0, long_runs = 0;
  for (const auto& c : cases) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case " << c.name;
    EXPECT_TRUE(std::filesystem::exists(find_resource_root() + "/" + c.scene)) << c.name << ": " << c.scene;
    EXPECT_FALSE(c.description.empty()) << c.name;
    if (c.expect == Expectation::kStable || c.expect == Expectation::kStableOrStopped) {
      EXPECT_FALSE(c.bounds_reason.empty()) << c.name << " states bounds without a reason";
    }
    if (c.expect != Expectation::kStable) {
      EXPECT_FALSE(c.message_terms.empty()) << c.name;
    }
    if (c.run_steps > 0) {
      EXPECT_TRUE(c.dt > 0 || c.dt_over_critical > 0) << c.name;
    }
    quick += c.quick ? 1 : 0;
    long_runs += c.long_run ? 1 : 0;
    EXPECT_FALSE(c.quick && c.long_run) << c.name << ": long runs are for the full suite";
  }
  EXPECT_GE(quick, 20);
  EXPECT_GE(long_runs, 2);
}

}  // namespace
}  // namespace periflex
