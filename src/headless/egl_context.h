// An OpenGL 3.3 core context with no window and no display server, through EGL.
// Tries, in order: the Mesa surfaceless platform, an EGL device (eglQueryDevicesEXT), the default
// display. The context has no surface: draw into a framebuffer object (see OffscreenTarget).
#pragma once

#include <string>

namespace periflex {

class EglContext {
 public:
  // Creates the context and makes it current on the calling thread. Throws std::runtime_error
  // naming the EGL step that failed and what was tried.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread (a context is current on one thread at a time).
  void make_current();
  // Releases it from the calling thread.
  void release();
  // "platform: surfaceless; GL: 4.5 (Core Profile) Mesa ...; renderer: llvmpipe ..."
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

}  // namespace periflex
