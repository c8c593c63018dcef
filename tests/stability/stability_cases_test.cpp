// Every quick case of the stability suite, run through the periflex program: each must end as its
// catalogue entry says (stable within its bounds, stopped with exit 3 and a diagnostic naming the
// expected quantity and a remedy, refused, or warned), with series.csv and summary.json intact.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/child_process.h"
#include "stability/stability_suite.h"
#include "support/text_match.h"

namespace periflex {

// Test names and failure messages show the case by name, not as bytes.
void PrintTo(const StabilityCase& c, std::ostream* os) { *os << c.name; }

namespace {

SuiteOptions test_options() {
  SuiteOptions o;
  o.program = PERIFLEX_BINARY;
  o.out_dir = (std::filesystem::current_path() / "stability_test_out").string();
  o.threads = 1;
  return o;
}

std::vector<StabilityCase> quick_cases() {
  std::vector<StabilityCase> quick;
  for (const auto& c : stability_cases())
    if (c.quick) quick.push_back(c);
  return quick;
}

class QuickCase : public ::testing::TestWithParam<StabilityCase> {};

TEST_P(QuickCase, BehavesAsExpected) {
  const StabilityCase& c = GetParam();
  const CaseResult r = run_stability_case(c, test_options());
  if (r.outcome == "skipped") GTEST_SKIP() << r.verdict;
  EXPECT_TRUE(r.as_expected) << c.name << ": expected " << r.expected << ", got " << r.outcome << " (exit "
                             << r.exit_code << ", signal " << r.signal << ")\n  " << r.verdict << "\n  message: "
                             << r.message << "\n  energy error " << r.relative_energy_error << " (bound "
                             << c.max_relative_energy_error << "), max violation " << r.max_violation << " (bound "
                             << c.max_violation << ")\n  output: " << test_options().out_dir << "/" << c.name;
  // whatever the outcome, never a crash and never a hang
  EXPECT_NE(r.outcome, "crashed") << r.message;
  EXPECT_NE(r.outcome, "hung") << r.message;
  EXPECT_TRUE(r.output_problems.empty()) << r.output_problems.front();
}

std::string case_test_name(const ::testing::TestParamInfo<StabilityCase>& info) {
  std::string name = info.param.name;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Stability, QuickCase, ::testing::ValuesIn(quick_cases()), case_test_name);

// 0.1 m x 0.04 m at dx = 1e-8 m: area / dx^2 = 4e13 particles. The refusal must give that count.
TEST(AbsurdSize, RefusalStatesTheParticleCount) {
  ChildLimits limits;
  limits.timeout_seconds = 30;
  limits.memory_bytes = 2e9;  // an attempt to allocate 4e13 particles fails here instead of swapping
  const auto r = run_child({PERIFLEX_BINARY, "check", std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/notched_plate.toml",
                            "--set", "flex_body.plate.grid_spacing=1e-8"},
                           limits);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  bool count_found = false;
  for (const std::string& number : testing::all_matches(r.output, R"([0-9]+(\.[0-9]+)?([eE][+]?[0-9]+)?)")) {
    const double v = std::strtod(number.c_str(), nullptr);
    // the estimate may count the grid's rows and columns (4000 x 10000 cells, +/- a row): within 1 %
    if (std::abs(v - 4e13) < 0.01 * 4e13) count_found = true;
  }
  EXPECT_TRUE(count_found) << "no particle count near 4e13 in: " << r.output;
  EXPECT_LT(r.wall_seconds, 10.0) << "refusing must not build anything";
}

// The subcommand, once the program registers it: a one-case run writes both tables.
TEST(StabilityCommand, WritesMarkdownAndCsvTables) {
  ChildLimits limits;
  limits.timeout_seconds = 60;
  const auto help = run_child({PERIFLEX_BINARY, "stability", "--list"}, limits);
  ASSERT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("spring_verlet_at_limit"), std::string::npos);
  const std::string out = (std::filesystem::current_path() / "stability_command_out").string();
  std::filesystem::remove_all(out);
  const auto r = run_child(
      {PERIFLEX_BINARY, "stability", "--quick", "--case", "spring_verlet_10x_limit", "--out", out}, limits);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out + "/stability.md"));
  EXPECT_TRUE(std::filesystem::exists(out + "/stability.csv"));
  EXPECT_NE(r.output.find("| spring_verlet_10x_limit |"), std::string::npos) << r.output;
}

// What every case would refuse is refused once, before any case runs (exit 2 naming the flag):
// the suite used to run all its cases, each failing the same way, and exit 1.
TEST(StabilityCommand, ProgramThatCannotRunAndTooManyThreadsAreRefusedUpFront) {
  ChildLimits limits;
  limits.timeout_seconds = 60;
  const std::string out = (std::filesystem::current_path() / "stability_refused_out").string();
  const auto missing =
      run_child({PERIFLEX_BINARY, "stability", "--quick", "--program", "/nonexistent", "--out", out}, limits);
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("'--program'"), std::string::npos) << missing.output;
  const auto threads = run_child({PERIFLEX_BINARY, "stability", "--quick", "--threads", "1024", "--out", out}, limits);
  EXPECT_EQ(threads.exit_code, 2) << threads.output;
  EXPECT_NE(threads.output.find("'--threads'"), std::string::npos) << threads.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/stability.csv"));
}

// SIGTERM (or Ctrl-C) during the suite: the case under way is told to stop and ends its own
// way, no further case starts, the table holds what ended, and the suite exits 143. It used to
// die at once and leave the case's run going in the background.
TEST(StabilityCommand, SigtermStopsTheCaseUnderWayAndStartsNoMore) {
  const std::string out = (std::filesystem::current_path() / "stability_sigterm_out").string();
  std::filesystem::remove_all(out);
  ChildLimits limits;
  limits.timeout_seconds = 300;
  // the signal once the first long run has started (its folder made)
  limits.interrupt = [&out] {
    return std::filesystem::exists(out + "/long_pendulum_1e6_steps/summary.json") ? SIGTERM : 0;
  };
  const auto r = run_child({PERIFLEX_BINARY, "stability", "--case", "long_pendulum", "--out", out}, limits);
  EXPECT_TRUE(r.interrupted);
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 143) << r.output;
  EXPECT_NE(r.output.find("stability suite interrupted by SIGTERM after 0 of 2 cases"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/long_pendulum_verlet_1e6_steps")) << "a case started after the signal";
  EXPECT_TRUE(std::filesystem::exists(out + "/stability.md"));
  // the case's own run stopped cleanly: its summary says so
  std::ifstream summary(out + "/long_pendulum_1e6_steps/summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"interrupted\""), std::string::npos) << text;
}

}  // namespace
}  // namespace periflex
