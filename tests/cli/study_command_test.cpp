// `periflex study` stopped by the user: Ctrl-C during the grid keeps what finished (study.csv and
// study.md, marked as stopped) and exits 130; a signal during the converged reference writes
// nothing and says so. The A02 study takes over two minutes, the flexible slider-crank's
// reference alone longer: both are stopped seconds in.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "child_run.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

long count_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  long lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Sends the signal and checks the study ends of it cleanly, exit 128 + the signal, saying `says`.
void expect_stopped_by(Child& child, int signal_number, const std::string& says) {
  child.send(signal_number);
  const ChildResult r = child.finish(60.0);
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.signal, 0) << r.output;
  EXPECT_EQ(r.exit_code, 128 + signal_number) << r.output;
  EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
}

TEST(StudyCommand, CtrlCDuringTheGridWritesTheRunsThatFinished) {
  const auto out = fresh_directory("study_sigint");
  Child child({"study", std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/studies/a02_double_four_bar.toml", "--out",
               out.string()});
  // the first verlet row: the symplectic Euler rows are done
  ASSERT_TRUE(child.wait_until([&] { return child.output_so_far().find("verlet projection") != std::string::npos; },
                               120.0))
      << child.output_so_far();
  expect_stopped_by(child, SIGINT, "interrupted by SIGINT");
  // header and at least the four symplectic Euler rows, fewer than the grid's 25
  const long rows = count_lines(out / "study.csv") - 1;
  EXPECT_GE(rows, 4);
  EXPECT_LT(rows, 25);
  const std::string markdown = read_text(out / "study.md");
  EXPECT_NE(markdown.find("Stopped before the end"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find(std::to_string(rows) + " runs finished"), std::string::npos) << markdown;
}

TEST(StudyCommand, SigtermDuringTheReferenceWritesNothing) {
  const auto out = fresh_directory("study_sigterm_reference");
  Child child({"study", std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/studies/flexible_slider_crank.toml", "--out",
               out.string()});
  ASSERT_TRUE(
      child.wait_until([&] { return child.output_so_far().find("reference: verlet") != std::string::npos; }, 60.0))
      << child.output_so_far();
  expect_stopped_by(child, SIGTERM, "during its reference run");
  EXPECT_FALSE(std::filesystem::exists(out / "study.csv"));
}

}  // namespace
}  // namespace periflex::testing
