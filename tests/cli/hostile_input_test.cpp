// The hostile-input corpus (tests/data/hostile/): scene files and command lines that crashed,
// hung, exhausted memory, wrote outside the output folder or gave the wrong exit code. Each runs
// as a child process of the built program, as a user types it, from a fresh working folder,
// under a 2 GB address-space cap and a 10 s limit. It must exit with the expected code (2, or 0
// with a warning), say where the problem is (file:line:column and key, --set, or the flag), die
// of no signal, print short lines, and write nothing outside the working folder's out/.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/sanitizer_build.h"
#include "support/text_match.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

// sanitizers reserve terabytes of address space and run several times slower
constexpr bool kSanitized = PERIFLEX_UNDER_SANITIZER;

constexpr double kTimeLimitSeconds = kSanitized ? 60.0 : 10.0;
constexpr rlim_t kAddressSpaceBytes = rlim_t(2) << 30;

// One entry of the corpus.
struct HostileCase {
  std::string name;                // for the test name
  std::string origin;              // file (and line) it came from
  int exit_code = 2;
  std::string expect;              // text the output must contain
  std::vector<std::string> args;   // with placeholders
  std::string scene_file;          // the scene file itself, when the case is one
  bool needs_cap = false;          // its limit comes from the 2 GB address-space cap ("2*")
};

// Splits a command line on blanks; single quotes group (and may hold nothing).
std::vector<std::string> split_arguments(const std::string& text) {
  std::vector<std::string> out;
  std::string word;
  bool in_word = false, quoted = false;
  for (char c : text) {
    if (c == '\'') {
      quoted = !quoted;
      in_word = true;
    } else if ((c == ' ' || c == '\t') && !quoted) {
      if (in_word) out.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) out.push_back(word);
  return out;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::string test_name(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

fs::path corpus_dir() { return fs::path(PERIFLEX_TEST_DATA) / "hostile"; }

// Every scene file of scenes/ (its "# expect:" and "# args:" header lines) and every line of
// commands.txt.
std::vector<HostileCase> load_corpus() {
  std::vector<HostileCase> cases;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(corpus_dir() / "scenes"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    HostileCase c;
    c.name = "scene_" + test_name(file.stem().string());
    c.origin = file.string();
    c.scene_file = file.string();
    c.args = {"check", file.string()};
    std::ifstream in(file, std::ios::binary);
    for (std::string line; std::getline(in, line) && line.rfind("#", 0) == 0;) {
      if (line.rfind("# expect: ", 0) == 0) {
        const std::string rest = line.substr(10);
        c.exit_code = std::stoi(rest.substr(0, rest.find(' ')));
        c.expect = trim(rest.substr(rest.find(' ') + 1));
      } else if (line.rfind("# args: ", 0) == 0) {
        c.args = split_arguments(line.substr(8));
        for (std::string& a : c.args)
          if (a == "{this}") a = file.string();
      }
    }
    cases.push_back(c);
  }
  std::ifstream table(corpus_dir() / "commands.txt");
  int number = 0;
  for (std::string line; std::getline(table, line);) {
    ++number;
    if (trim(line).empty() || line[0] == '#') continue;
    const size_t bar1 = line.find(" | "), bar2 = line.find(" | ", bar1 + 3);
    if (bar1 == std::string::npos || bar2 == std::string::npos) continue;
    HostileCase c;
    c.origin = "commands.txt:" + std::to_string(number);
    c.exit_code = std::stoi(line.substr(0, bar1));
    c.needs_cap = line.substr(0, bar1).find('*') != std::string::npos;
    c.expect = trim(line.substr(bar1 + 3, bar2 - bar1 - 3));
    c.args = split_arguments(line.substr(bar2 + 3));
    c.name = "line_" + std::to_string(number) + "_" + test_name(c.args.empty() ? "" : c.args.front());
    cases.push_back(c);
  }
  return cases;
}

// Special files the command lines name, made on first use in a folder of this test process
// (ctest runs cases of the corpus in parallel processes) and removed when it ends.
class Fixtures {
 public:
  Fixtures() : root_(fs::current_path() / ("hostile_fixtures_" + std::to_string(::getpid()))) {}
  ~Fixtures() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }

  // The path of fixture `name`, made the first time it is asked for.
  fs::path get(const std::string& name) {
    fs::create_directories(root_);
    if (name == "dir") return make(root_ / "dir", [](const fs::path& p) { fs::create_directories(p); });
    if (name == "file") return make(root_ / "plain.txt", [](const fs::path& p) { std::ofstream(p) << "not a folder\n"; });
    if (name == "fifo") return make(root_ / "fifo.toml", [](const fs::path& p) { ::mkfifo(p.c_str(), 0600); });
    // 20 GB that take no room on disk
    if (name == "sparse")
      return make(root_ / "sparse.toml", [](const fs::path& p) {
        std::ofstream(p).close();
        fs::resize_file(p, 20ull << 30);
      });
    // a regular file just over the scene-size cap
    if (name == "big")
      return make(root_ / "big.toml", [](const fs::path& p) {
        std::ofstream out(p, std::ios::binary);
        const std::string line(1023, '#');
        for (int k = 0; k < 17 * 1024; ++k) out << line << '\n';
      });
    if (name == "zero_link") return make(root_ / "zero.toml", [](const fs::path& p) { fs::create_symlink("/dev/zero", p); });
    if (name == "loop_link") return make(root_ / "loop.toml", [](const fs::path& p) { fs::create_symlink(p, p); });
    return root_ / name;
  }

 private:
  template <class Make>
  fs::path make(const fs::path& path, Make&& how) {
    if (!fs::exists(fs::symlink_status(path))) how(path);
    return path;
  }
  fs::path root_;
};

Fixtures& fixtures() {
  static Fixtures f;
  return f;
}

std::string substitute(std::string text, const fs::path& out) {
  const std::pair<std::string, std::string> fixed[] = {{"{scenes}", std::string(PERIFLEX_SOURCE_ROOT) + "/scenes"},
                                                       {"{hostile}", corpus_dir().string()},
                                                       {"{out}", out.string()}};
  auto replace = [&](const std::string& key, const std::string& value) {
    for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  };
  for (const auto& [key, value] : fixed) replace(key, value);
  for (const char* name : {"file", "dir", "fifo", "sparse", "big", "zero_link", "loop_link"}) {
    std::string key = "{";
    key.append(name).append("}");
    if (text.find(key) != std::string::npos) replace(key, fixtures().get(name).string());
  }
  return text;
}

struct ChildResult {
  bool exited = false;
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;
  double seconds = 0.0;
  std::string output;
};

// Runs the program with `args` in `cwd` under the address-space cap, stdout and stderr
// captured together; kills it at the time limit.
ChildResult run_child(const std::vector<std::string>& args, const fs::path& cwd) {
  ChildResult result;
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return result;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    if (::chdir(cwd.c_str()) != 0) ::_exit(120);
    if (!kSanitized) {
      struct rlimit cap {kAddressSpaceBytes, kAddressSpaceBytes};
      ::setrlimit(RLIMIT_AS, &cap);
    }
    const int null_fd = ::open("/dev/null", O_RDONLY);
    ::dup2(null_fd, 0);
    ::dup2(pipe_fds[1], 1);
    ::dup2(pipe_fds[1], 2);
    ::close(pipe_fds[0]);
    std::vector<char*> argv;
    // PERIFLEX_BINARY_UNDER_TEST runs the corpus against another build (to compare releases)
    const char* other = std::getenv("PERIFLEX_BINARY_UNDER_TEST");
    std::string program = other != nullptr && *other != '\0' ? other : PERIFLEX_BINARY;
    argv.push_back(program.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(program.c_str(), argv.data());
    ::_exit(121);
  }
  ::close(pipe_fds[1]);
  // read until the child closes its end or the time runs out
  char buffer[4096];
  while (true) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > kTimeLimitSeconds) {
      result.timed_out = true;
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
      break;
    }
    struct pollfd p {pipe_fds[0], POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    if (result.output.size() < (1u << 20)) result.output.append(buffer, static_cast<size_t>(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exited = WIFEXITED(status);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return result;
}

// Every path under `root`.
std::set<std::string> tree(const fs::path& root) {
  std::set<std::string> paths;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator(); it.increment(ec))
    paths.insert(it->path().lexically_relative(root).string());
  return paths;
}

class HostileInput : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileInput, RefusedLocatedBoundedAndContained) {
  const HostileCase& c = GetParam();
  SCOPED_TRACE(c.origin);
  // a sanitizer cannot run under the cap, and without it the memory limit is the machine's
  if (c.needs_cap && kSanitized) GTEST_SKIP() << "the limit this case reaches comes from the address-space cap";
  // a working folder three levels deep, so that "../../../x" still lands inside the sandbox
  const fs::path sandbox = fs::current_path() / ("hostile_run_" + c.name);
  fs::remove_all(sandbox);
  const fs::path cwd = sandbox / "a" / "b" / "c";
  fs::create_directories(cwd);
  std::vector<std::string> args;
  for (const std::string& a : c.args) args.push_back(substitute(a, cwd / "out" / "run"));

  const ChildResult r = run_child(args, cwd);
  SCOPED_TRACE(r.output.substr(0, 2000));

  // bounded, no signal, the expected exit code
  ASSERT_FALSE(r.timed_out) << "still running after " << kTimeLimitSeconds << " s";
  ASSERT_TRUE(r.exited) << "killed by signal " << r.signal;
  EXPECT_EQ(r.exit_code, c.exit_code);
  EXPECT_NE(r.output.find(c.expect), std::string::npos) << "expected to read: " << c.expect;
  // in the sanitizer build, no report from the program either
  for (const char* report : {"runtime error:", "ERROR: AddressSanitizer", "ERROR: LeakSanitizer"})
    EXPECT_EQ(r.output.find(report), std::string::npos) << report;

  // located: file:line:column and key, --set, or the flag; never "<input>"
  EXPECT_EQ(r.output.find("<input>"), std::string::npos);
  if (c.exit_code == 2) {
    // ours ("periflex: error: <where>: ...") or the option parser's ("--fps: Value inf not in ...")
    const char* located =
        R"((periflex: error: (command line: key '|--set: key '|[^\s]+:\d+(:\d+)?: |[^\s]+: key '|/[^\s]*: ))|(^|\n)--[a-z-]+: )";
    EXPECT_TRUE(testing::contains_match(r.output, located)) << "the message does not say where";
    if (!c.scene_file.empty() && c.expect.find(".toml") == std::string::npos) {
      // a scene's own problem is located in that scene
      EXPECT_NE(r.output.find(fs::path(c.scene_file).filename().string() + ":"), std::string::npos);
    }
  } else if (!c.scene_file.empty()) {
    EXPECT_NE(r.output.find("warning:"), std::string::npos);
    EXPECT_TRUE(testing::contains_match(r.output, R"(\.toml:\d+:\d+: key '[^']+': warning: )"))
        << "the warning does not say where";
  }

  // short lines: no number printed in 300 digits, no echo of megabytes of input
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) EXPECT_LT(line.size(), 2000u);
  EXPECT_FALSE(testing::contains_match(r.output, "[0-9]{40}")) << "a number printed in 40 digits or more";

  // nothing outside the working folder's out/
  for (const std::string& path : tree(sandbox)) {
    const bool allowed = path == "a" || path == "a/b" || path == "a/b/c" || path.rfind("a/b/c/out", 0) == 0;
    EXPECT_TRUE(allowed) << "written outside the output folder: " << path;
  }
  EXPECT_FALSE(fs::exists("/tmp/periflex-absolute"));
  fs::remove_all(sandbox);
}

// gtest prints the case by its origin rather than its bytes.
void PrintTo(const HostileCase& c, std::ostream* out) { *out << c.origin; }

std::string case_name(const ::testing::TestParamInfo<HostileCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Corpus, HostileInput, ::testing::ValuesIn(load_corpus()), case_name);

// The corpus covers every class with at least 80 entries.
TEST(HostileCorpus, HoldsAtLeastEightyCases) { EXPECT_GE(load_corpus().size(), 80u); }

}  // namespace
}  // namespace periflex
