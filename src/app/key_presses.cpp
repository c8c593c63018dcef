#include "app/key_presses.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace periflex {

namespace {

std::vector<KeyPress>& pending() {
  static std::vector<KeyPress> presses;
  return presses;
}

void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (action == GLFW_PRESS || action == GLFW_REPEAT) pending().push_back({key, mods, action == GLFW_REPEAT});
}

}  // namespace

void install_key_presses(GLFWwindow* window) { glfwSetKeyCallback(window, on_key); }

std::vector<KeyPress> take_key_presses() {
  std::vector<KeyPress> out;
  out.swap(pending());
  return out;
}

}  // namespace periflex
