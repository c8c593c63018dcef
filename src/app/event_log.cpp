#include "app/event_log.h"

#include <chrono>
#include <cstdio>

namespace periflex {

double EventLog::now_seconds() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

void EventLog::add(const std::string& line) {
  char stamp[32];
  std::snprintf(stamp, sizeof stamp, "[%7.2f] ", now_seconds() - start_);
  std::string text = stamp + line;
  std::lock_guard<std::mutex> lock(mutex_);
  // stderr under the lock too, so lines from two threads never interleave
  if (echo_) std::fprintf(stderr, "gui: %s\n", text.c_str());
  lines_.push_back(std::move(text));
  if (lines_.size() > capacity_) lines_.pop_front();
  ++total_;
}

std::vector<std::string> EventLog::lines() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {lines_.begin(), lines_.end()};
}

long EventLog::total() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return total_;
}

}  // namespace periflex
