// Key presses between two frames, as GLFW reports them. Dear ImGui 1.86 reads the keys held at
// each frame, so a tap shorter than a frame (a quick press while a large scene draws at a few
// frames per second) would be lost; the window's shortcuts read these instead. Main thread only.
// Internal to src/app/.
#pragma once

#include <vector>

struct GLFWwindow;

namespace periflex {

struct KeyPress {
  int key = 0;          // GLFW_KEY_*
  int mods = 0;         // GLFW_MOD_*
  bool repeat = false;  // the system's auto-repeat of a held key
};

// Installs the key callback; call before ImGui_ImplGlfw_InitForOpenGL, which chains to it.
void install_key_presses(GLFWwindow* window);
// The presses since the last call, oldest first.
std::vector<KeyPress> take_key_presses();

}  // namespace periflex
