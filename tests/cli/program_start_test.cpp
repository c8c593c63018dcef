// The program runs in the process it was started as: it never starts itself again (it once did,
// to set libgomp's waiting policy before the library loaded; the solver's own team of threads,
// core/thread_pool.h, needs no environment). Seen from outside: the running program's
// environment is the one it was given.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "run_program.h"

namespace periflex::testing {
namespace {

TEST(ProgramStart, RunsInTheProcessItWasStartedAsWithItsEnvironment) {
  const auto out = fresh_directory("program_start");
  const std::string scene_file = scene("pendulum.toml"), out_dir = out.string();
  const pid_t pid = fork();
  if (pid == 0) {
    unsetenv("OMP_WAIT_POLICY");
    unsetenv("GOMP_SPINCOUNT");
    execl(PERIFLEX_BINARY, "periflex", "run", scene_file.c_str(), "--until", "1000", "--quiet", "--out",
          out_dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // the run has begun once it writes its series
  for (int k = 0; k < 300 && !std::filesystem::exists(out / "series.csv"); ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::string environment = read_text("/proc/" + std::to_string(pid) + "/environ");
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << "status " << status;
  // entries are separated by NUL characters: one per line to search
  for (char& c : environment)
    if (c == '\0') c = '\n';
  environment = "\n" + environment;
  EXPECT_NE(environment.find("\nPATH="), std::string::npos) << "the environment was not read: " << environment;
  EXPECT_EQ(environment.find("\nGOMP_SPINCOUNT="), std::string::npos) << environment;
  EXPECT_EQ(environment.find("\nOMP_WAIT_POLICY="), std::string::npos) << environment;
}

}  // namespace
}  // namespace periflex::testing
