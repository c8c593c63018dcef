// The compute context at the end of a process: a driver may tear its EGL down before the
// program's own objects are destroyed (NVIDIA's does, from an exit handler), and a context or
// device destroyed after that must not take the process down with it.
#include <EGL/egl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "core/resources.h"
#include "gpu/gl_bond_force_device.h"

namespace periflex::testing {
namespace {

// The display torn down under a live context and device (as a driver's exit handler does), then
// both destroyed: the process goes on and exits normally.
TEST(GlComputeContextDeathTest, OutlivingTheDriversDisplayIsNoCrash) {
  try {
    GlComputeContext probe(find_resource_root());
  } catch (const std::exception& e) {
    GTEST_SKIP() << "no OpenGL compute context with fp64 here: " << e.what();
  }
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        auto context = std::make_shared<GlComputeContext>(find_resource_root());
        auto device = std::make_unique<GlBondForceDevice>(context);
        EGLDisplay display = EGL_NO_DISPLAY;
        {
          EglContext::Scope current(context->egl());
          display = eglGetCurrentDisplay();
        }
        eglTerminate(display);
        device.reset();
        context.reset();
        std::exit(7);
      },
      ::testing::ExitedWithCode(7), "");
}

}  // namespace
}  // namespace periflex::testing
