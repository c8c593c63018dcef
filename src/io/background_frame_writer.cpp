#include "io/background_frame_writer.h"

#include <utility>

namespace periflex {

BackgroundFrameWriter::BackgroundFrameWriter(std::unique_ptr<FrameWriter> inner, size_t capacity)
    : inner_(std::move(inner)), capacity_(capacity > 0 ? capacity : 1), thread_([this] { run(); }) {}

BackgroundFrameWriter::~BackgroundFrameWriter() {
  // not closed (an error elsewhere ended the recording): what is queued is dropped
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
    queue_.clear();
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool BackgroundFrameWriter::ready() const {
  std::lock_guard<std::mutex> lock(mutex_);
  // after an error too: the next write() reports it
  return error_ || queue_.size() + (busy_ ? 1 : 0) < capacity_;
}

void BackgroundFrameWriter::rethrow_locked() {
  if (error_) std::rethrow_exception(error_);
}

void BackgroundFrameWriter::write(const RgbaImage& frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return error_ || queue_.size() + (busy_ ? 1 : 0) < capacity_; });
  rethrow_locked();
  queue_.push_back(frame);
  changed_.notify_all();
}

void BackgroundFrameWriter::close() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    closing_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  rethrow_locked();
  inner_->close();
}

long BackgroundFrameWriter::frames_written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_;
}

void BackgroundFrameWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return closing_ || !queue_.empty(); });
    // after an error the rest is dropped: close() and write() report it
    if (queue_.empty() || error_) return;
    RgbaImage frame = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    std::exception_ptr failure;
    try {
      inner_->write(frame);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
    busy_ = false;
    if (failure) error_ = failure;
    else ++written_;
    changed_.notify_all();
  }
}

}  // namespace periflex
