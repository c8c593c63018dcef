// `periflex study` as a user runs it: exit code 0, the three files, and the plot or a clear word
// that there is none. Skipped (with the reason) while the program does not offer the command.
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/child_process.h"

namespace periflex {
namespace {

struct ProgramRun {
  int exit_code = -1;
  std::string output;
};

ProgramRun run_program(const std::string& arguments) {
  ProgramRun run;
  const std::string command = std::string("'") + PERIFLEX_BINARY + "' " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST(StudyCommand, WritesCsvMarkdownAndPlotOrSaysWhy) {
  const auto dir = std::filesystem::temp_directory_path() / ("periflex_study_command_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto study = dir / "study.toml";
  std::ofstream(study) << "[study]\nscene = \"" << PERIFLEX_SOURCE_ROOT
                       << "/scenes/studies/models/pendulum.toml\"\nreference = \"pendulum_exact\"\n"
                          "end_time = 0.2\ncompare_interval = 0.02\n"
                          "[[method]]\nintegrator = \"rk4\"\ndt = [1e-2, 5e-3]\ncorrection = \"none\"\n";
  // the subcommand list of --help names it at the start of a line
  ASSERT_NE(run_program("--help").output.find("\n  study "), std::string::npos);
  const ProgramRun run = run_program("study '" + study.string() + "' --out '" + (dir / "out").string() + "' --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "study.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "study.md"));
  // with gnuplot installed, the plot (a PNG file larger than a header); else a clear word
  if (!find_program("gnuplot").empty()) {
    std::ifstream png(dir / "out" / "study.png", std::ios::binary);
    std::string head(8, '\0');
    png.read(head.data(), 8);
    EXPECT_EQ(head, "\x89PNG\r\n\x1a\n") << run.output;
    std::error_code missing;
    EXPECT_GT(std::filesystem::file_size(dir / "out" / "study.png", missing), 1000u) << missing.message();
  } else {
    EXPECT_NE(run.output.find("no plot made"), std::string::npos) << run.output;
  }
  // a study file that does not exist is bad input
  EXPECT_EQ(run_program("study '" + (dir / "missing.toml").string() + "'").exit_code, 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace periflex
