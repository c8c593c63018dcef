// Runs the periflex program as a child process the way a user's shell would, with a time limit,
// and optionally stops it with a signal part-way: the exit status, the signal if one ended it,
// and everything it printed.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace periflex::testing {

struct ChildResult {
  int exit_code = -1;      // exit status; -1 when a signal ended it
  int signal = 0;          // the signal that ended it, 0 if it exited
  bool timed_out = false;  // killed by the time limit
  double seconds = 0.0;    // wall time until it ended
  std::string output;      // standard output and error, interleaved
};

class Child {
 public:
  // Starts `PERIFLEX_BINARY args...` with its output going to a file.
  explicit Child(const std::vector<std::string>& args) {
    std::vector<std::string> all{PERIFLEX_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    start(all);
  }
  // Starts `/bin/sh -c command`, a command line as a user types it, in a process group of its
  // own, so that a time limit stops the shell and every program it started.
  static std::unique_ptr<Child> shell(const std::string& command) {
    std::unique_ptr<Child> child(new Child());
    child->group_ = true;
    child->start({"/bin/sh", "-c", command});
    return child;
  }
  ~Child() {
    if (pid_ > 0 && !ended_) {
      ::kill(group_ ? -pid_ : pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ignored;
    std::filesystem::remove(log_, ignored);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  // What the child has printed so far.
  std::string output_so_far() const {
    std::ifstream in(log_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  void send(int signal_number) const { ::kill(pid_, signal_number); }

  // Polls `ready` every 10 ms until it holds or the child ends or `limit` seconds pass; true when it held.
  bool wait_until(const std::function<bool()>& ready, double limit) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit);
    while (std::chrono::steady_clock::now() < deadline) {
      if (ready()) return true;
      if (poll_end()) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  // Waits for the end, killing the child after `limit` seconds.
  ChildResult finish(double limit) {
    wait_until([] { return false; }, limit);
    if (!ended_) {
      result_.timed_out = true;
      ::kill(group_ ? -pid_ : pid_, SIGKILL);
      reap(0);
    }
    std::ifstream in(log_);
    std::stringstream text;
    text << in.rdbuf();
    result_.output = text.str();
    return result_;
  }

 private:
  Child() = default;
  void start(std::vector<std::string> all) {
    static int counter = 0;
    log_ = std::filesystem::temp_directory_path() /
           ("periflex-child-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".log");
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    if (group_) {
      posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
      posix_spawnattr_setpgroup(&attributes, 0);
    }
    start_ = std::chrono::steady_clock::now();
    if (posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ) != 0) pid_ = -1;
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
  }
  bool poll_end() {
    if (ended_ || pid_ <= 0) return true;
    return reap(WNOHANG);
  }
  bool reap(int flags) {
    int status = 0;
    if (::waitpid(pid_, &status, flags) != pid_) return false;
    ended_ = true;
    result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (WIFEXITED(status)) result_.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result_.signal = WTERMSIG(status);
    return true;
  }

  pid_t pid_ = -1;
  bool group_ = false;  // the child leads a process group of its own
  bool ended_ = false;
  std::filesystem::path log_;
  std::chrono::steady_clock::time_point start_;
  ChildResult result_;
};

// Runs the program to its end, or kills it after `limit` seconds.
inline ChildResult run_child(const std::vector<std::string>& args, double limit) {
  Child child(args);
  return child.finish(limit);
}

}  // namespace periflex::testing
