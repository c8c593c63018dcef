// A step of a small rigid system allocates no memory once warmed up: the IFToMM A01 pendulum
// and A02 double four-bar with rk4 and projection, 1000 steps each after a warm-up (the A02
// steps pass two of its singular positions, where the rank of the Jacobian changes).
//
// This test program replaces the C allocation functions with counting ones that forward to the
// C library's own (operator new, std::vector and Eigen all end in malloc), counting only while
// a test asks. Under a sanitizer, whose run-time owns malloc, the test is skipped.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <string>

#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "support/sanitizer_build.h"

#define PERIFLEX_COUNT_ALLOCATIONS (!PERIFLEX_UNDER_SANITIZER)

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
// a function of its own: a debugger that stops here shows who allocated
__attribute__((noinline)) void counted() { allocations.fetch_add(1, std::memory_order_relaxed); }
[[maybe_unused]] void count() {
  if (counting.load(std::memory_order_relaxed)) counted();
}
}  // namespace

#if PERIFLEX_COUNT_ALLOCATIONS
// glibc's entry points behind malloc and its siblings
extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* p, size_t size);
void* __libc_memalign(size_t alignment, size_t size);

void* malloc(size_t size) {
  count();
  return __libc_malloc(size);
}
void* calloc(size_t n, size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size) {
  count();
  return __libc_realloc(p, size);
}
void* aligned_alloc(size_t alignment, size_t size) {
  count();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) {
  count();
  *out = __libc_memalign(alignment, size);
  return *out ? 0 : 12;  // ENOMEM
}
}
#endif

namespace periflex {
namespace {

// Heap allocations during `steps` steps of the scene, after `warm_up` steps.
long allocations_in_steps(SceneDef scene, int warm_up, int steps) {
  Simulation sim(scene);
  sim.initialize();
  for (int k = 0; k < warm_up; ++k) sim.step();
  allocations = 0;
  counting = true;
  for (int k = 0; k < steps; ++k) sim.step();
  counting = false;
  return allocations.load();
}

SceneDef benchmark_scene(const std::string& name) {
  return load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/benchmarks/" + name);
}

constexpr const char* kNoCounting = "allocation counting is off under a sanitizer";

// the counter itself sees an allocation (else a zero below would prove nothing)
TEST(StepAllocation, CounterSeesAnAllocation) {
  if (!PERIFLEX_COUNT_ALLOCATIONS) GTEST_SKIP() << kNoCounting;
  allocations = 0;
  counting = true;
  auto* p = new std::string(100, 'x');
  counting = false;
  delete p;
  EXPECT_GE(allocations.load(), 1);
}

TEST(StepAllocation, PendulumRk4StepsDoNotAllocate) {
  if (!PERIFLEX_COUNT_ALLOCATIONS) GTEST_SKIP() << kNoCounting;
  SceneDef scene = benchmark_scene("a01_pendulum.toml");
  scene.solver.integrator = "rk4";
  scene.solver.dt = 0.01;
  EXPECT_EQ(allocations_in_steps(scene, 100, 1000), 0);
}

TEST(StepAllocation, DoubleFourBarRk4StepsDoNotAllocate) {
  if (!PERIFLEX_COUNT_ALLOCATIONS) GTEST_SKIP() << kNoCounting;
  const SceneDef scene = benchmark_scene("a02_double_four_bar.toml");
  ASSERT_EQ(scene.solver.integrator, "rk4");
  EXPECT_EQ(allocations_in_steps(scene, 100, 1000), 0);
}

}  // namespace
}  // namespace periflex
