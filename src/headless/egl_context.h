// An OpenGL core context (3.3 unless asked for a later version) with no window and no display
// server, through EGL.
// Tries, in order: the Mesa surfaceless platform, an EGL device (eglQueryDevicesEXT), the default
// display. The context has no surface: draw into a framebuffer object (see OffscreenTarget).
#pragma once

#include <new>
#include <string>

namespace periflex {

class EglContext {
 public:
  // Creates an OpenGL major.minor core context and makes it current on the calling thread. Throws
  // std::runtime_error naming the EGL step that failed and what was tried.
  explicit EglContext(int major = 3, int minor = 3);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread (a context is current on one thread at a time).
  void make_current();
  // Releases it from the calling thread.
  void release();
  // Makes a context current for a scope and gives the calling thread back the context it had, or
  // none (another part of the program, e.g. the off-screen recorder, may have its own current; a
  // context released after each scope may be used from any one thread at a time).
  class Scope {
   public:
    explicit Scope(EglContext& context);
    // For destructors: where the context cannot be made current (the driver already torn down
    // at the process's exit, a lost context), nothing is thrown and current() is false.
    Scope(EglContext& context, std::nothrow_t);
    ~Scope();
    bool current() const { return current_; }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    void* display_ = nullptr;
    void* draw_ = nullptr;
    void* read_ = nullptr;
    void* context_ = nullptr;
    bool switched_ = false;
    bool current_ = true;
    int error_ = 0;  // EGL's error when it could not be made current
  };

  // "platform: surfaceless; GL: 4.5 (Core Profile) Mesa ...; renderer: llvmpipe ..."
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

}  // namespace periflex
