// Stand-ins for GPUs that fail, for tests of the program as typed: preloaded (LD_PRELOAD) into
// `periflex`, this library
// - answers GL_CONTEXT_LOST from glGetError once it has been asked PERIFLEX_TEST_GL_LOST_AFTER
//   times (a context lost mid-run);
// - answers NVIDIA's free-memory query (GL_NVX_gpu_memory_info) with PERIFLEX_TEST_GPU_FREE_KB
//   (a GPU with that little memory free);
// and passes every other call to the real driver. (The program calls libOpenGL's entry points
// directly, so the preloaded symbols stand first.)
#include <dlfcn.h>

#include <atomic>
#include <cstdlib>

namespace {

long number_from(const char* name) {
  const char* text = std::getenv(name);
  return text ? std::atol(text) : -1L;
}

}  // namespace

extern "C" unsigned glGetError() {
  using GetError = unsigned (*)();
  static const GetError real = reinterpret_cast<GetError>(dlsym(RTLD_NEXT, "glGetError"));
  static const long lost_after = number_from("PERIFLEX_TEST_GL_LOST_AFTER");
  static std::atomic<long> calls{0};
  constexpr unsigned kContextLost = 0x0507;  // GL_CONTEXT_LOST
  if (lost_after >= 0 && ++calls > lost_after) return kContextLost;
  return real ? real() : 0u;
}

extern "C" void glGetIntegerv(unsigned name, int* data) {
  using GetIntegerv = void (*)(unsigned, int*);
  static const GetIntegerv real = reinterpret_cast<GetIntegerv>(dlsym(RTLD_NEXT, "glGetIntegerv"));
  static const long free_kb = number_from("PERIFLEX_TEST_GPU_FREE_KB");
  constexpr unsigned kCurrentAvailableVideoMemory = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
  if (free_kb >= 0 && name == kCurrentAvailableVideoMemory) {
    *data = static_cast<int>(free_kb);
    return;
  }
  if (real) real(name, data);
}
