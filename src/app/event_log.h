// The log panel's lines: every change the user, a key or a script makes is written here
// (and to stderr) by whichever thread applied it. Thread-safe; no GL.
#pragma once

#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace periflex {

class EventLog {
 public:
  explicit EventLog(bool echo_to_stderr = true, size_t capacity = 500)
      : echo_(echo_to_stderr), capacity_(capacity) {}

  // Appends one line, prefixed with the wall-clock seconds since the log was made.
  void add(const std::string& line);
  // A copy of the kept lines, oldest first, and how many lines were ever added
  // (the panel scrolls to the bottom when that number grows).
  std::vector<std::string> lines() const;
  long total() const;

 private:
  mutable std::mutex mutex_;
  std::deque<std::string> lines_;
  long total_ = 0;
  bool echo_;
  size_t capacity_;
  double start_ = now_seconds();
  static double now_seconds();
};

}  // namespace periflex
