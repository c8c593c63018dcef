// What the window's parts (gui_app.cpp, gui_script_runner.cpp, gui_input.cpp, gui_capture.cpp)
// share: how near the pointer must be to grab a particle, and the wall clock.
#pragma once

#include <chrono>

namespace periflex::gui_parts {

// pixels within which the mouse grabs a particle
constexpr double kPickPixels = 6.0;

inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace periflex::gui_parts
