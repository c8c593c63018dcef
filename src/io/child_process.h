// Runs a program as a child process with a wall-clock limit and a memory limit, capturing its
// combined output. The stability suite runs every case this way, so a case that crashes, hangs
// or tries to allocate without bound is observed and reported instead of taking the suite down.
#pragma once

#include <string>
#include <vector>

namespace periflex {

struct ChildLimits {
  double timeout_seconds = 120.0;     // the child (and its process group) is killed after this
  double memory_bytes = 4e9;          // address-space limit (RLIMIT_AS); <= 0: none
  std::vector<std::string> environment;  // extra "NAME=value" entries set in the child
  std::string working_directory;         // the child starts in this folder (empty: the caller's)
};

struct ChildResult {
  int exit_code = -1;        // when the child exited normally
  int signal = 0;            // when a signal ended it (SIGSEGV, SIGABRT, SIGKILL after a timeout)
  bool timed_out = false;
  bool started = false;      // false: fork or exec failed (output says why)
  double wall_seconds = 0.0;
  std::string output;        // stdout and stderr interleaved
};

// Runs argv[0] (a path) with the arguments argv[1..]; blocks until it ends or the limit passes.
ChildResult run_child(const std::vector<std::string>& argv, const ChildLimits& limits);

// The path of the running program (/proc/self/exe), for commands that re-run themselves.
std::string current_executable();

// The path of an executable `name` on PATH (as a shell would find it), or empty.
std::string find_program(const std::string& name);

}  // namespace periflex
