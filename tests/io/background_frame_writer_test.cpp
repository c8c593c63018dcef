// BackgroundFrameWriter: frames reach the inner writer in order and all of them by close(); it
// holds no more than its capacity (ready() says when the window may hand it another); an error
// of the writing thread comes back from write() and close().
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "io/background_frame_writer.h"

namespace periflex {
namespace {

// An inner writer that keeps the first byte of each frame, waits while `held`, and fails at
// frame `fail_at` (when >= 0).
struct Gate {
  std::mutex mutex;
  std::condition_variable opened;
  bool held = false;
  std::vector<int> seen;
  int fail_at = -1;
};

class GatedWriter : public FrameWriter {
 public:
  explicit GatedWriter(Gate& gate) : gate_(gate) {}
  void write(const RgbaImage& frame) override {
    std::unique_lock<std::mutex> lock(gate_.mutex);
    gate_.opened.wait(lock, [this] { return !gate_.held; });
    if (static_cast<int>(gate_.seen.size()) == gate_.fail_at) throw std::runtime_error("disk full");
    gate_.seen.push_back(frame.pixels[0]);
  }
  void close() override { closed = true; }
  long frames_written() const override { return static_cast<long>(gate_.seen.size()); }
  bool closed = false;

 private:
  Gate& gate_;
};

RgbaImage frame(int id) {
  RgbaImage image;
  image.resize(2, 2);
  image.pixels[0] = static_cast<uint8_t>(id);
  return image;
}

void open_gate(Gate& gate) {
  {
    std::lock_guard<std::mutex> lock(gate.mutex);
    gate.held = false;
  }
  gate.opened.notify_all();
}

TEST(BackgroundFrameWriter, EveryFrameInOrderByClose) {
  Gate gate;
  auto inner = std::make_unique<GatedWriter>(gate);
  GatedWriter* raw = inner.get();
  BackgroundFrameWriter writer(std::move(inner), 2);
  for (int i = 0; i < 50; ++i) writer.write(frame(i));
  writer.close();
  EXPECT_TRUE(raw->closed);
  ASSERT_EQ(gate.seen.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(gate.seen[i], i);
  EXPECT_EQ(writer.frames_written(), 50);
}

TEST(BackgroundFrameWriter, HoldsNoMoreThanItsCapacityWhileTheEncoderIsBusy) {
  Gate gate;
  gate.held = true;
  BackgroundFrameWriter writer(std::make_unique<GatedWriter>(gate), 2);
  EXPECT_TRUE(writer.ready());
  writer.write(frame(1));
  writer.write(frame(2));
  // the encoder holds one, one waits: full, and the window is told so without waiting
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(writer.ready());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(100));
  open_gate(gate);
  writer.close();
  EXPECT_EQ(gate.seen, (std::vector<int>{1, 2}));
}

TEST(BackgroundFrameWriter, TheEncodersErrorComesBackFromWriteAndClose) {
  Gate gate;
  gate.fail_at = 1;
  BackgroundFrameWriter writer(std::make_unique<GatedWriter>(gate), 1);
  writer.write(frame(0));
  writer.write(frame(1));  // fails on the thread
  // ready() turns true so that the window's next write() hears of it
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  bool thrown = false;
  while (!thrown && std::chrono::steady_clock::now() < until) {
    if (!writer.ready()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    try {
      writer.write(frame(2));
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "disk full");
      thrown = true;
    }
  }
  EXPECT_TRUE(thrown);
  EXPECT_THROW(writer.close(), std::runtime_error);
  EXPECT_EQ(gate.seen, (std::vector<int>{0}));
}

TEST(BackgroundFrameWriter, DroppedUnclosedWithoutWritingTheQueue) {
  Gate gate;
  gate.held = true;
  std::thread opener;
  {
    BackgroundFrameWriter writer(std::make_unique<GatedWriter>(gate), 3);
    writer.write(frame(1));
    writer.write(frame(2));
    writer.write(frame(3));
    opener = std::thread([&gate] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      open_gate(gate);
    });
  }
  opener.join();
  // the frame the thread had taken is written; the queued ones are dropped
  EXPECT_LE(gate.seen.size(), 1u);
}

}  // namespace
}  // namespace periflex
