#include "io/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>

extern char** environ;

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

// Output beyond this is dropped from the middle: the start says what ran, the end how it ended.
constexpr size_t kMaxOutputBytes = 1 << 20;

void append_bounded(std::string& out, const char* data, size_t n) {
  out.append(data, n);
  if (out.size() > 2 * kMaxOutputBytes) {
    const std::string tail = out.substr(out.size() - kMaxOutputBytes / 2);
    out.resize(kMaxOutputBytes / 2);
    out += "\n[... output shortened ...]\n" + tail;
  }
}

}  // namespace

std::string current_executable() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : path.string();
}

std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  size_t begin = 0;
  for (;;) {
    const size_t end = dirs.find(':', begin);
    const std::string dir = dirs.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error) && access(candidate.c_str(), X_OK) == 0)
      return candidate.string();
    if (end == std::string::npos) return "";
    begin = end + 1;
  }
}

pid_t start_child(const std::vector<std::string>& argv, const ChildStreams& streams, std::string& error) {
  if (argv.empty()) {
    error = "no program given";
    return -1;
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (streams.input >= 0) posix_spawn_file_actions_adddup2(&actions, streams.input, STDIN_FILENO);
  if (streams.output >= 0) {
    posix_spawn_file_actions_adddup2(&actions, streams.output, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, streams.output, STDERR_FILENO);
  }
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, args[0], &actions, &attributes, args.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    error = "cannot start " + argv[0] + ": " + std::strerror(rc);
    return -1;
  }
  return pid;
}

ChildResult run_child(const std::vector<std::string>& argv, const ChildLimits& limits) {
  ChildResult result;
  if (argv.empty()) {
    result.output = "no program given";
    return result;
  }

  // everything the child needs is prepared before fork: between fork and exec only
  // async-signal-safe calls are allowed (the parent may have other threads)
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> env_storage;
  for (char** e = environ; e && *e; ++e) {
    bool replaced = false;
    for (const auto& extra : limits.environment) {
      const auto eq = extra.find('=');
      if (eq != std::string::npos && std::strncmp(*e, extra.c_str(), eq + 1) == 0) replaced = true;
    }
    if (!replaced) env_storage.emplace_back(*e);
  }
  for (const auto& extra : limits.environment) env_storage.push_back(extra);
  std::vector<char*> envp;
  for (auto& e : env_storage) envp.push_back(e.data());
  envp.push_back(nullptr);
  struct rlimit memory_limit {};
  const bool limit_memory = limits.memory_bytes > 0;
  if (limit_memory) {
    // a limit past what rlim_t holds is no limit (the cast itself would be undefined)
    const bool representable = limits.memory_bytes < static_cast<double>(RLIM_INFINITY);
    memory_limit.rlim_cur = representable ? static_cast<rlim_t>(limits.memory_bytes) : RLIM_INFINITY;
    memory_limit.rlim_max = memory_limit.rlim_cur;
  }

  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) {
    result.output = std::string("pipe failed: ") + std::strerror(errno);
    return result;
  }

  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    result.output = std::string("fork failed: ") + std::strerror(errno);
    return result;
  }
  if (pid == 0) {
    // child: own process group (so a timeout kills its threads and children too),
    // output into the pipe, bounded memory, then the program
    setpgid(0, 0);
    dup2(pipe_fds[1], STDOUT_FILENO);
    dup2(pipe_fds[1], STDERR_FILENO);
    if (limit_memory) setrlimit(RLIMIT_AS, &memory_limit);
    if (!limits.working_directory.empty() && chdir(limits.working_directory.c_str()) != 0) {
      const char message[] = "cannot enter the working directory\n";
      ssize_t ignored = write(STDERR_FILENO, message, sizeof message - 1);
      (void)ignored;
      _exit(127);
    }
    execve(args[0], args.data(), envp.data());
    const char message[] = "exec failed\n";
    ssize_t ignored = write(STDERR_FILENO, message, sizeof message - 1);
    (void)ignored;
    _exit(127);
  }
  result.started = true;
  close(pipe_fds[1]);

  // read until the pipe closes or the deadline passes
  auto deadline = start + std::chrono::duration<double>(limits.timeout_seconds);
  // the caller's interrupt, passed on once; then the child has a grace period to stop
  const auto pass_interrupt = [&] {
    if (result.interrupted || !limits.interrupt) return;
    const int signal_number = limits.interrupt();
    if (signal_number == 0) return;
    kill(-pid, signal_number);
    result.interrupted = true;
    const decltype(deadline) grace_end = Clock::now() + std::chrono::duration<double>(limits.interrupt_grace_seconds);
    deadline = std::min(deadline, grace_end);
  };
  const double poll_ms = limits.interrupt ? 100.0 : 1000.0;
  char buffer[65536];
  bool open = true;
  while (open) {
    pass_interrupt();
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0) {
      result.timed_out = true;
      break;
    }
    struct pollfd p {pipe_fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(std::min(left * 1000.0 + 1.0, poll_ms)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
    if (n > 0) {
      append_bounded(result.output, buffer, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      open = false;
    }
  }
  if (result.timed_out) kill(-pid, SIGKILL);

  // reap it; a child that closed its output but keeps running is still bound by the deadline
  int status = 0;
  while (true) {
    const pid_t done = waitpid(pid, &status, result.timed_out ? 0 : WNOHANG);
    if (done == pid) break;
    pass_interrupt();
    if (done < 0 && errno != EINTR) break;
    if (Clock::now() >= deadline && !result.timed_out) {
      result.timed_out = true;
      kill(-pid, SIGKILL);
      continue;
    }
    if (!result.timed_out) usleep(2000);
  }
  close(pipe_fds[0]);
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
    if (result.exit_code == 127 && result.output.find("exec failed") != std::string::npos) result.started = false;
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  return result;
}

}  // namespace periflex
