// Child processes (io/child_process.h): start_child hands the child the descriptors it is given,
// puts it in a process group of its own and reports a program that cannot start; find_program
// looks along PATH, and along the usual folders when PATH is unset; run_child passes the caller's
// interrupt on.
#include "io/child_process.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <string>

namespace periflex {
namespace {

TEST(ChildProcess, StartedChildReadsAndWritesTheGivenDescriptorsInItsOwnGroup) {
  int in[2], out[2];
  ASSERT_EQ(pipe(in), 0);
  ASSERT_EQ(pipe(out), 0);
  std::string error;
  const pid_t pid = start_child({"/bin/sh", "-c", "read line; echo \"got $line\"; echo oops >&2; exit 3"},
                                {in[0], out[1]}, error);
  close(in[0]);
  close(out[1]);
  ASSERT_GT(pid, 0) << error;
  // a group of its own: a terminal's Ctrl-C for periflex does not reach it
  EXPECT_EQ(getpgid(pid), pid);
  EXPECT_NE(getpgid(pid), getpgid(0));
  const std::string line = "hello\n";
  ASSERT_EQ(write(in[1], line.data(), line.size()), static_cast<ssize_t>(line.size()));
  close(in[1]);
  std::string output;
  char buffer[256];
  for (ssize_t n; (n = read(out[0], buffer, sizeof buffer)) > 0;) output.append(buffer, static_cast<size_t>(n));
  close(out[0]);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  // standard output and standard error both on the output descriptor
  EXPECT_EQ(output, "got hello\noops\n");
}

// A memory limit past what the limit's type holds is no limit: the child runs (the cast of such
// a value was undefined and killed the child).
TEST(ChildProcess, MemoryLimitBeyondTheLimitTypeIsNoLimit) {
  ChildLimits limits;
  limits.timeout_seconds = 60.0;
  limits.memory_bytes = 1e39;
  const ChildResult r = run_child({"/bin/sh", "-c", "echo ran"}, limits);
  EXPECT_EQ(r.signal, 0) << r.output;
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("ran"), std::string::npos) << r.output;
}

TEST(ChildProcess, ProgramThatCannotStartIsReportedNamingIt) {
  std::string error;
  EXPECT_EQ(start_child({"/nonexistent/ffmpeg", "-version"}, {}, error), -1);
  EXPECT_NE(error.find("/nonexistent/ffmpeg"), std::string::npos) << error;
  EXPECT_EQ(start_child({}, {}, error), -1);
}

TEST(ChildProcess, FindProgramLooksAlongPathOrTheUsualFolders) {
  const std::string sh = find_program("sh");
  ASSERT_FALSE(sh.empty());
  EXPECT_EQ(access(sh.c_str(), X_OK), 0);
  EXPECT_TRUE(find_program("no-such-program-periflex").empty());
  // without PATH a shell still finds sh in /usr/bin or /bin
  const char* saved = std::getenv("PATH");
  const std::string path = saved ? saved : "";
  unsetenv("PATH");
  const std::string found = find_program("sh");
  if (saved) setenv("PATH", path.c_str(), 1);
  EXPECT_TRUE(found == "/usr/bin/sh" || found == "/bin/sh") << found;
}

// The caller's interrupt is passed on once: a child that handles it stops its own way (its exit
// status and last words kept); one that ignores it is killed when the grace period ends, long
// before its timeout.
TEST(ChildProcess, InterruptIsPassedOnAndAChildThatIgnoresItIsKilledAfterTheGrace) {
  auto start = std::chrono::steady_clock::now();
  const auto after = [&start](double seconds) {
    return [&start, seconds] {
      return std::chrono::steady_clock::now() - start > std::chrono::duration<double>(seconds) ? SIGTERM : 0;
    };
  };
  ChildLimits limits;
  limits.timeout_seconds = 60.0;
  limits.interrupt = after(0.3);
  ChildResult r = run_child({"/bin/sh", "-c", "trap 'echo stopping; exit 7' TERM; while :; do sleep 0.05; done"}, limits);
  EXPECT_TRUE(r.interrupted);
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 7);
  EXPECT_NE(r.output.find("stopping"), std::string::npos) << r.output;
  EXPECT_LT(r.wall_seconds, 5.0);

  // the interrupt 0.3 s after this child starts too, once its shell has set its trap (timed
  // from the test's start, it came at once, and a loaded machine delivered it before the trap)
  limits.interrupt_grace_seconds = 0.5;
  start = std::chrono::steady_clock::now();
  r = run_child({"/bin/sh", "-c", "trap '' TERM; while :; do sleep 0.05; done"}, limits);
  EXPECT_TRUE(r.interrupted);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.signal, SIGKILL);
  EXPECT_LT(r.wall_seconds, 10.0);
}

}  // namespace
}  // namespace periflex
