#include "gpu/gl_compute_context.h"

#include <filesystem>
#include <stdexcept>

#include "render/gl.h"

namespace periflex {

namespace {

// An EGL context of OpenGL 4.3, the first version with compute shaders; the error says so
EglContext make_compute_context() {
  try {
    return EglContext(4, 3);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("no OpenGL 4.3 context for compute shaders: ") + e.what());
  }
}

}  // namespace

GlComputeContext::GlComputeContext(const std::string& resource_root)
    : egl_(make_compute_context()), resource_root_(resource_root) {
  // current on no thread between passes: each pass takes it on the thread it runs on
  egl_.release();
}

GlComputeContext::~GlComputeContext() {
  // at the process's exit a driver may have torn its EGL down first: then there is nothing to free
  EglContext::Scope current(egl_, std::nothrow);
  if (!current.current()) return;
  for (unsigned program : programs_)
    if (program) glDeleteProgram(program);
}

unsigned GlComputeContext::bond_force_program(DevicePrecision precision) {
  unsigned& program = programs_[precision == DevicePrecision::kFp32 ? 1 : 0];
  if (program) return program;
  EglContext::Scope current(egl_);
  const auto path = std::filesystem::path(resource_root_) / "shaders" / "pd_bond_forces.comp";
  if (precision == DevicePrecision::kFp32)
    program = load_compute_program(path.string(), "", "#define PD_FP32 1\n");
  else  // a shader that does not compile here most often meets a driver without fp64 in its GLSL
    program = load_compute_program(path.string(), "\n(does the driver have fp64? solver.precision = \"fp32\" needs none)");
  return program;
}

}  // namespace periflex
