// A frame writer that writes on a thread of its own: the window hands it a frame and goes on
// drawing while an encoder as slow as ffmpeg's GIF palette (a third of a second a frame at
// 1280x800) takes its time. It holds at most `capacity` frames; the window asks ready() before it
// takes another recorded frame from the simulation thread, so a slow encoder holds the simulation
// back, never the window (its clicks, its keys).
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "io/frame_writer.h"

namespace periflex {

class BackgroundFrameWriter : public FrameWriter {
 public:
  BackgroundFrameWriter(std::unique_ptr<FrameWriter> inner, size_t capacity);
  ~BackgroundFrameWriter() override;

  // True while another frame fits without waiting, or once the writing thread has failed.
  bool ready() const;
  // Queues the frame (waits while the queue is full). Throws the error the writing thread met,
  // once it has met one.
  void write(const RgbaImage& frame) override;
  // Writes what is queued, then closes the inner writer; throws the first error met.
  void close() override;
  // Frames the inner writer has accepted.
  long frames_written() const override;

 private:
  void run();
  void rethrow_locked();

  std::unique_ptr<FrameWriter> inner_;
  size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<RgbaImage> queue_;
  bool closing_ = false;
  bool busy_ = false;  // the thread holds a frame taken from the queue
  long written_ = 0;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace periflex
