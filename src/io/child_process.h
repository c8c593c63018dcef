// Child processes, the one place the program starts them:
//  - run_child runs a program with a wall-clock limit and a memory limit, capturing its combined
//    output. The stability suite runs every case this way, so a case that crashes, hangs or tries
//    to allocate without bound is observed and reported instead of taking the suite down;
//  - start_child starts one that runs beside the program (ffmpeg reading the movie's frames),
//    with its input and output on descriptors the caller gives.
// Both put the child in a process group of its own: a timeout kills the whole group, and a
// terminal's Ctrl-C reaches periflex only, which then ends its children its own way.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

namespace periflex {

struct ChildLimits {
  double timeout_seconds = 120.0;     // the child (and its process group) is killed after this
  double memory_bytes = 4e9;          // address-space limit (RLIMIT_AS); <= 0: none
  std::vector<std::string> environment;  // extra "NAME=value" entries set in the child
  std::string working_directory;         // the child starts in this folder (empty: the caller's)
  // Asked every tenth of a second while the child runs: a signal (SIGINT, SIGTERM) the caller
  // received and passes on to the child's process group, once, or 0. The child then has
  // interrupt_grace_seconds (within the timeout) to stop its own way before it is killed.
  std::function<int()> interrupt;
  double interrupt_grace_seconds = 30.0;
};

struct ChildResult {
  int exit_code = -1;        // when the child exited normally
  int signal = 0;            // when a signal ended it (SIGSEGV, SIGABRT, SIGKILL after a timeout)
  bool timed_out = false;
  bool interrupted = false;  // the caller's interrupt was passed on to it
  bool started = false;      // false: fork or exec failed (output says why)
  double wall_seconds = 0.0;
  std::string output;        // stdout and stderr interleaved
};

// Runs argv[0] (a path) with the arguments argv[1..]; blocks until it ends or the limit passes.
ChildResult run_child(const std::vector<std::string>& argv, const ChildLimits& limits);

// Where a started child reads and writes: descriptors dup'ed onto its standard input and onto
// its standard output and error (-1: the parent's own).
struct ChildStreams {
  int input = -1;
  int output = -1;
};

// Starts argv[0] (a path) with the arguments argv[1..] and returns at once: its pid, or -1 with
// the reason in `error`. The caller waits for it (waitpid).
pid_t start_child(const std::vector<std::string>& argv, const ChildStreams& streams, std::string& error);

// The path of the running program (/proc/self/exe), for commands that re-run themselves.
std::string current_executable();

// The path of an executable `name` on PATH (as a shell would find it; /usr/local/bin:/usr/bin:/bin
// when PATH is unset), or empty.
std::string find_program(const std::string& name);

}  // namespace periflex
