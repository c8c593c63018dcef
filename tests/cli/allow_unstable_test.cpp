// `--allow-unstable` as typed: an explicit step a hundred times the critical one on the notched
// plate runs (instead of being refused) until it diverges, and ends with the numerical-failure
// diagnostic: exit 3, the quantity named, every row of series.csv whole and finite, summary.json
// saying numerical_failure.
#include <gtest/gtest.h>

#include <cmath>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"
#include "support/text_match.h"

namespace periflex::testing {
namespace {

constexpr double kUnstableRunSeconds = 120.0;

TEST(AllowUnstable, NotchedPlatePastTheStableStepDivergesWithTheDiagnostic) {
  const auto out = fresh_directory("allow_unstable");
  // 6.15e-5 s is 100 times the plate's critical step; 2e-3 s is 32.5 such steps
  const auto r = run_child({"run", scene("notched_plate.toml"), "--dt", "6.15e-5", "--allow-unstable", "--until",
                            "2e-3", "--out", out.string(), "--quiet"},
                           kUnstableRunSeconds);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 3) << r.output;
  // the diagnostic names the quantity that grew, and says the step was past the limit on purpose
  EXPECT_TRUE(testing::contains_match(
      r.output, R"(numerical failure: (kinetic energy|energy|state \(positions / velocities\)) at step [0-9]+)"))
      << r.output;
  EXPECT_NE(r.output.find("solver.allow_unstable"), std::string::npos) << r.output;

  const auto summary = read_summary(out / "summary.json");
  ASSERT_FALSE(summary.is_discarded()) << "summary.json does not parse";
  EXPECT_EQ(summary["status"], "numerical_failure");
  EXPECT_EQ(summary["exit_code"], 3);

  // rows whole and finite, at least the one at t = 0, none past the failure
  const Series series = read_series(out / "series.csv");
  EXPECT_EQ(series.incomplete_rows, 0);
  ASSERT_GE(series.rows.size(), 1u);
  for (const auto& row : series.rows)
    for (double v : row) EXPECT_TRUE(std::isfinite(v));
  const int t = series.column("t");
  EXPECT_LT(series.rows.back()[t], 2e-3);
}

// The same step without the flag is refused before the run (exit 2, naming --dt): the flag is
// what lets it run.
TEST(AllowUnstable, WithoutTheFlagTheStepIsRefusedUpFront) {
  const auto out = fresh_directory("allow_unstable_refused");
  const auto r = run_child(
      {"run", scene("notched_plate.toml"), "--dt", "6.15e-5", "--until", "2e-3", "--out", out.string(), "--quiet"},
      kUnstableRunSeconds);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--dt"), std::string::npos) << r.output;
}

// The flag and sub-steps contradict each other: refused, naming both keys.
TEST(AllowUnstable, FlagWithAutoSubstepIsRefused) {
  const auto r = run_child({"run", scene("notched_plate.toml"), "--allow-unstable", "--set",
                            "solver.auto_substep=true", "--until", "1e-5", "--out",
                            fresh_directory("allow_unstable_substep").string(), "--quiet"},
                           kUnstableRunSeconds);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("allow_unstable"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("auto_substep"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace periflex::testing
