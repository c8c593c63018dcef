// The ImGui context lock: taken twice on one thread it throws (a freeze otherwise), and it is
// free again for any thread once released. No GL needed.
#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

#include "render/renderer.h"

namespace periflex {
namespace {

TEST(ImGuiContextLock, TakenTwiceOnOneThreadThrowsInsteadOfFreezing) {
  ImGuiContextLock outer;
  EXPECT_THROW({ ImGuiContextLock inner; }, std::logic_error);
}

TEST(ImGuiContextLock, ReleasedLockIsFreeForAnotherThread) {
  { ImGuiContextLock first; }
  bool taken = false;
  std::thread other([&taken] {
    ImGuiContextLock lock;
    taken = true;
  });
  other.join();
  EXPECT_TRUE(taken);
  // and again on this one
  ImGuiContextLock again;
  SUCCEED();
}

}  // namespace
}  // namespace periflex
