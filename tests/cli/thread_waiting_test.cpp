// The program's OpenMP threads spin briefly before they sleep (core/thread_waiting.h): started
// without either libgomp variable, periflex starts itself again with GOMP_SPINCOUNT set (seen
// in the environment of the running process); a user's own choice is kept as it is.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "core/thread_waiting.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

// Starts a long pendulum run with the libgomp variables removed and `policy` (if any) set as
// OMP_WAIT_POLICY; returns the environment of the running program once it has started its
// run (the restart, if any, done), then stops it.
std::string environment_of_run(const char* policy, const std::string& tag) {
  const auto out = fresh_directory("thread_waiting_" + tag);
  const std::string scene_file = scene("pendulum.toml"), out_dir = out.string();
  const pid_t pid = fork();
  if (pid == 0) {
    unsetenv("OMP_WAIT_POLICY");
    unsetenv("GOMP_SPINCOUNT");
    if (policy) setenv("OMP_WAIT_POLICY", policy, 1);
    execl(PERIFLEX_BINARY, "periflex", "run", scene_file.c_str(), "--until", "1000", "--quiet", "--out",
          out_dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // the run has begun once it writes its series (after any restart)
  std::string environment;
  for (int k = 0; k < 300 && !std::filesystem::exists(out / "series.csv"); ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  environment = read_text("/proc/" + std::to_string(pid) + "/environ");
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << "status " << status;
  // entries are separated by NUL characters: one per line to search
  for (char& c : environment)
    if (c == '\0') c = '\n';
  return "\n" + environment;
}

TEST(ThreadWaiting, ProgramStartsItselfAgainWithABriefSpin) {
  const std::string environment = environment_of_run(nullptr, "default");
  EXPECT_NE(environment.find(std::string("\nGOMP_SPINCOUNT=") + kSpinTurns + "\n"), std::string::npos) << environment;
  EXPECT_EQ(environment.find("\nOMP_WAIT_POLICY="), std::string::npos);
}

TEST(ThreadWaiting, UsersOwnWaitPolicyIsKept) {
  const std::string environment = environment_of_run("passive", "passive");
  EXPECT_NE(environment.find("\nOMP_WAIT_POLICY=passive\n"), std::string::npos) << environment;
  EXPECT_EQ(environment.find("\nGOMP_SPINCOUNT="), std::string::npos);
}

}  // namespace
}  // namespace periflex::testing
