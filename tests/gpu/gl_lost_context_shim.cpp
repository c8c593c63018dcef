// A stand-in for a GPU whose context is lost mid-run, for tests of the program as typed:
// preloaded (LD_PRELOAD) into `periflex`, it answers GL_CONTEXT_LOST from glGetError once it has
// been asked PERIFLEX_TEST_GL_LOST_AFTER times, and passes every other call to the real driver.
// (The program calls libOpenGL's entry points directly, so the preloaded symbol stands first.)
#include <dlfcn.h>

#include <atomic>
#include <cstdlib>

using GlGetError = unsigned (*)();

extern "C" unsigned glGetError() {
  static const GlGetError real = reinterpret_cast<GlGetError>(dlsym(RTLD_NEXT, "glGetError"));
  static const long lost_after = [] {
    const char* text = std::getenv("PERIFLEX_TEST_GL_LOST_AFTER");
    return text ? std::atol(text) : -1L;
  }();
  static std::atomic<long> calls{0};
  constexpr unsigned kContextLost = 0x0507;  // GL_CONTEXT_LOST
  if (lost_after >= 0 && ++calls > lost_after) return kContextLost;
  return real ? real() : 0u;
}
