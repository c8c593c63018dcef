// A small multi-producer queue of requests to the simulation thread. The user interface
// pushes; the simulation thread takes everything pending between two steps and applies it
// in the order it was pushed, so a request never lands in the middle of a step.
// No GL here: the unit tests run without a display.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <vector>

namespace periflex {

template <class T>
class CommandQueue {
 public:
  // Appends one request and wakes a consumer waiting in wait_for().
  void push(T command) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_.push_back(std::move(command));
    }
    ready_.notify_one();
  }

  // Takes every pending request, oldest first (empty when there is none).
  std::vector<T> drain() {
    std::vector<T> out;
    std::lock_guard<std::mutex> lock(mutex_);
    out.reserve(pending_.size());
    for (T& c : pending_) out.push_back(std::move(c));
    pending_.clear();
    return out;
  }

  // Blocks until a request is pending or the timeout passes; true when one is pending.
  // The paused simulation thread sleeps here instead of spinning.
  template <class Rep, class Period>
  bool wait_for(const std::chrono::duration<Rep, Period>& timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return ready_.wait_for(lock, timeout, [this] { return !pending_.empty(); });
  }

  // Number of pending requests (a hint: it may change as soon as it is returned).
  size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> pending_;
};

}  // namespace periflex
