// An OpenGL 4.3 core context for compute, off-screen through EGL (headless/egl_context.h), with
// the bond-force program compiled in it. One per process is enough: every body's device shares it.
#pragma once

#include <memory>
#include <string>

#include "headless/egl_context.h"

namespace periflex {

class GlComputeContext {
 public:
  // Creates the context and compiles shaders/pd_bond_forces.comp under resource_root. Throws
  // std::runtime_error saying what is missing: no EGL display, no OpenGL 4.3 core context (compute
  // shaders), a shader that does not compile (no fp64 in the driver's GLSL), or a missing file.
  explicit GlComputeContext(const std::string& resource_root);
  ~GlComputeContext();
  GlComputeContext(const GlComputeContext&) = delete;
  GlComputeContext& operator=(const GlComputeContext&) = delete;

  EglContext& egl() { return egl_; }
  unsigned bond_force_program() const { return bond_force_program_; }
  // "OpenGL compute fp64; GL: 4.5 (Core Profile) Mesa ...; renderer: llvmpipe ..."
  const std::string& description() const { return description_; }

 private:
  EglContext egl_;
  unsigned bond_force_program_ = 0;
  std::string description_;
};

}  // namespace periflex
