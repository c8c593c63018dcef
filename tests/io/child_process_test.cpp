// Child processes (io/child_process.h): start_child hands the child the descriptors it is given,
// puts it in a process group of its own and reports a program that cannot start; find_program
// looks along PATH, and along the usual folders when PATH is unset.
#include "io/child_process.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

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

}  // namespace
}  // namespace periflex
