// Every `periflex run`, `check`, `sweep` and `study` command shown in a code block of README.md
// and docs/*.md, run as typed in a shell (continuation lines joined, comments dropped, a window
// opened after `&&` left out), in the order a reader meets them (README first, then the docs by
// name) from one working folder holding the scenes, so that a command may use what an earlier
// one wrote. Each must exit 0: a documented command that fails is a defect of the program or of
// its documentation. Commands that draw need the off-screen renderer (and --movie ffmpeg). The
// window's commands (`gui`, `play`) are left to the tests of tests/app, which run it under Xvfb.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"
#include "support/sanitizer_build.h"
#include "support/text_match.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

struct DocumentedCommand {
  std::string where;    // file:line
  std::string command;  // as typed
};

// The commands of the fenced code blocks of one Markdown file.
void commands_of(const fs::path& file, std::vector<DocumentedCommand>& out) {
  const char* program_command = R"(^periflex (run|check|sweep|study)\b)";
  std::ifstream in(file);
  bool fenced = false;
  std::string line, pending;
  int number = 0, start = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t first = line.find_first_not_of(' ');
    const std::string text = first == std::string::npos ? "" : line.substr(first);
    if (text.rfind("```", 0) == 0) {
      fenced = !fenced;
      continue;
    }
    if (!fenced) continue;
    if (pending.empty()) {
      if (!testing::contains_match(text, program_command)) continue;
      start = number;
    }
    // a trailing backslash continues the command on the next line
    const bool continued = !text.empty() && text.back() == '\\';
    pending += (pending.empty() ? "" : " ") + (continued ? text.substr(0, text.size() - 1) : text);
    if (continued) continue;
    std::string command = pending.substr(0, pending.find(" #"));
    command = command.substr(0, command.find(" && periflex play"));
    command.erase(command.find_last_not_of(' ') + 1);
    out.push_back({file.filename().string() + ":" + std::to_string(start), command});
    pending.clear();
  }
}

std::vector<DocumentedCommand> documented_commands() {
  const fs::path root = PERIFLEX_SOURCE_ROOT;
  std::vector<fs::path> docs;
  for (const auto& entry : fs::directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md") docs.push_back(entry.path());
  std::sort(docs.begin(), docs.end());
  docs.insert(docs.begin(), root / "README.md");
  std::vector<DocumentedCommand> commands;
  for (const fs::path& file : docs) commands_of(file, commands);
  return commands;
}

#ifndef PERIFLEX_TEST_RENDER
bool draws(const std::string& command) {
  for (const char* flag : {"--render", "--frames", "--movie", "--snapshot-at", "--screenshot"})
    if (command.find(flag) != std::string::npos) return true;
  return false;
}
#endif

TEST(DocumentedCommands, EveryOneRunsAsTypedToExitZero) {
#if PERIFLEX_UNDER_SANITIZER
  GTEST_SKIP() << "full runs of the shipped scenes: the optimised build runs them";
#endif
  const std::vector<DocumentedCommand> commands = documented_commands();
  // the README's quick tour and the docs' examples: a shrinking list says the reader lost some
  ASSERT_GE(commands.size(), 15u);
  const fs::path dir = fresh_directory("documented_commands");
  fs::create_directory_symlink(fs::path(PERIFLEX_SOURCE_ROOT) / "scenes", dir / "scenes");
  const std::string program_folder = fs::path(PERIFLEX_BINARY).parent_path().string();
  int ran = 0;
  for (const DocumentedCommand& c : commands) {
#ifndef PERIFLEX_TEST_RENDER
    if (draws(c.command)) continue;
#endif
    if (c.command.find("--movie") != std::string::npos && !have_program("ffmpeg")) continue;
    const std::string shell = "cd '" + dir.string() + "' && PATH='" + program_folder + "':\"$PATH\" && " + c.command;
    const ChildResult r = Child::shell(shell)->finish(300.0);
    EXPECT_FALSE(r.timed_out) << c.where << ": " << c.command;
    EXPECT_EQ(r.exit_code, 0) << c.where << ": " << c.command << "\n" << r.output;
    ++ran;
  }
  EXPECT_GE(ran, 8) << "too few of the documented commands could run in this build";
}

}  // namespace
}  // namespace periflex::testing
