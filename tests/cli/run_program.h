// Runs the periflex program in a shell and captures its exit code and combined output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace periflex::testing {

struct ProgramResult {
  int exit_code = -1;
  std::string output;
};

// A command line run by the shell, its standard error with its output.
inline ProgramResult run_periflex_command(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  ProgramResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

inline ProgramResult run_periflex(const std::string& arguments) {
  return run_periflex_command(std::string(PERIFLEX_BINARY) + " " + arguments);
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A fresh, empty directory under the test's working directory.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::current_path() / ("cli_test_out_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string scene(const std::string& file) { return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + file; }

}  // namespace periflex::testing
