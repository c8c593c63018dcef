// The command line as a user meets it: exit codes, messages and the files a run leaves.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "run_program.h"
#include "support/json_text.h"

namespace periflex::testing {
namespace {

TEST(CommandLine, HelpAndVersionExitZero) {
  const auto help = run_periflex("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("run"), std::string::npos);
  EXPECT_NE(help.output.find("check"), std::string::npos);
  const auto version = run_periflex("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.output.find(PERIFLEX_VERSION), std::string::npos);
}

TEST(CommandLine, UnknownOptionIsBadInput) {
  EXPECT_EQ(run_periflex("run " + scene("pendulum.toml") + " --no-such-option").exit_code, 2);
  EXPECT_EQ(run_periflex("frobnicate").exit_code, 2);
}

TEST(CommandLine, MissingSceneFileIsBadInputNamingTheFile) {
  const auto r = run_periflex("check /nonexistent/dir/scene.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent/dir/scene.toml"), std::string::npos) << r.output;
}

TEST(CommandLine, BadOverrideIsBadInputNamingTheKey) {
  const auto r = run_periflex("check " + scene("pendulum.toml") + " --set solver.no_such_key=3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no_such_key"), std::string::npos) << r.output;
}

TEST(CommandLine, BadOptionValuesAreBadInput) {
  EXPECT_EQ(run_periflex("run " + scene("pendulum.toml") + " --dt -1 --quiet").exit_code, 2);
  EXPECT_EQ(run_periflex("run " + scene("pendulum.toml") + " --integrator nonsense --quiet").exit_code, 2);
  EXPECT_EQ(run_periflex("run " + scene("pendulum.toml") + " --render --size 12by7 --quiet").exit_code, 2);
}

TEST(CommandLine, CheckDescribesTheModel) {
  const auto r = run_periflex("check " + scene("slider_crank.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("degrees of freedom"), std::string::npos);
  EXPECT_NE(r.output.find("constraint equations"), std::string::npos);
  EXPECT_NE(r.output.find("active modules"), std::string::npos);
  // A driven slider-crank has no degree of freedom left.
  EXPECT_NE(r.output.find("degrees of freedom    0"), std::string::npos) << r.output;
}

// check names the peridynamic model of every flexible body; a state-based Poisson ratio outside
// the range of its plane condition is refused with exit 2, naming the key.
TEST(CommandLine, CheckNamesEachFlexibleBodysModel) {
  const auto r = run_periflex("check " + scene("notched_plate_models.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("'bond_based': bond-based, plane stress, poisson_ratio = 1/3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'state_based': state-based (LPS), plane stress, poisson_ratio = 0.3"), std::string::npos)
      << r.output;
  const auto strain = run_periflex("check " + scene("notched_plate_models.toml") +
                                   " --set flex_body.state_based.material.plane=strain"
                                   " --set flex_body.state_based.material.poisson_ratio=0.5");
  EXPECT_EQ(strain.exit_code, 2) << strain.output;
  EXPECT_NE(strain.output.find("flex_body.state_based.material.poisson_ratio"), std::string::npos) << strain.output;
  EXPECT_NE(strain.output.find("plane strain"), std::string::npos) << strain.output;
  // a softening body is named as the bond-based law with bilinear softening it is
  const auto softening = run_periflex("check " + scene("concrete_beam_3pb.toml"));
  ASSERT_EQ(softening.exit_code, 0) << softening.output;
  EXPECT_NE(softening.output.find(": bond-based, bilinear softening, plane"), std::string::npos) << softening.output;
  // the same value is admissible in plane stress
  EXPECT_EQ(run_periflex("check " + scene("notched_plate_models.toml") +
                         " --set flex_body.state_based.material.poisson_ratio=0.5")
                .exit_code,
            0);
}

// Parses a CSV body into rows of numbers, failing on any row with a wrong column count.
std::vector<std::vector<double>> parse_csv(const std::string& text, std::vector<std::string>& header) {
  std::vector<std::vector<double>> rows;
  std::stringstream lines(text);
  std::string line;
  bool first = true;
  while (std::getline(lines, line)) {
    std::stringstream cells(line);
    std::string cell;
    if (first) {
      while (std::getline(cells, cell, ',')) header.push_back(cell);
      first = false;
      continue;
    }
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    EXPECT_EQ(row.size(), header.size()) << "row " << rows.size() << ": " << line;
    rows.push_back(row);
  }
  return rows;
}

TEST(CommandLine, RunWritesSeriesAndSummary) {
  const auto out = fresh_directory("run");
  const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.5 --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Quiet or not on a terminal: a single final line naming the output directory.
  EXPECT_NE(r.output.find(out.string()), std::string::npos);
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;

  std::vector<std::string> header;
  const auto rows = parse_csv(read_text(out / "series.csv"), header);
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(header.front(), "t");
  for (const char* column : {"kinetic", "potential_gravity", "dissipated", "external_work", "energy_balance",
                             "violation_position", "violation_velocity"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  }
  EXPECT_NEAR(rows.back()[0], 0.5, 1e-9);
  for (const auto& row : rows)
    for (double v : row) EXPECT_TRUE(std::isfinite(v));

  const auto summary = testing::parse_json(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["exit_code"], 0);
  EXPECT_GT(summary["steps"].get<long>(), 0);
  EXPECT_NEAR(summary["simulated_time"].get<double>(), 0.5, 1e-9);
  const auto modules = summary["active_modules"];
  for (const auto& m : modules) EXPECT_EQ(m.get<std::string>().rfind("pd_", 0), std::string::npos) << m;
}

TEST(CommandLine, SetOverridesChangeTheRun) {
  const auto out = fresh_directory("override");
  const auto r = run_periflex("run " + scene("pendulum.toml") + " --set solver.end_time=0.2 --quiet --out " +
                              out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = testing::parse_json(read_text(out / "summary.json"));
  EXPECT_NEAR(summary["simulated_time"].get<double>(), 0.2, 1e-9);
}

TEST(CommandLine, KilledRunLeavesCompleteRowsAndValidSummary) {
  // a run far longer than the test (its 1e7 rows above the default budget, raised knowingly)
  const auto out = fresh_directory("killed");
  const std::string command = std::string(PERIFLEX_BINARY) + " run " + scene("double_pendulum.toml") +
                              " --until 100000 --dt 1e-4 --set limits.max_output_rows=1e8 --quiet --out " + out.string() + " >/dev/null 2>&1";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Let it write for a while, then kill it without warning.
  for (int waited = 0; waited < 100 && !std::filesystem::exists(out / "series.csv"); ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);

  const std::string text = read_text(out / "series.csv");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "the last row is incomplete";
  std::vector<std::string> header;
  const auto rows = parse_csv(text, header);
  EXPECT_GE(rows.size(), 2u);
  const auto summary = testing::parse_json(read_text(out / "summary.json"));  // throws if invalid
  EXPECT_EQ(summary["status"], "running");
}

}  // namespace
}  // namespace periflex::testing
