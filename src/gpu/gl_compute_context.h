// An OpenGL 4.3 core context for compute, off-screen through EGL (headless/egl_context.h), with
// the bond-force program of each precision compiled in it when first asked for. One per process is
// enough: every body's device shares it.
#pragma once

#include <memory>
#include <string>

#include "headless/egl_context.h"
#include "pd/bond_force_device.h"

namespace periflex {

class GlComputeContext {
 public:
  // Creates the context. Throws std::runtime_error saying what is missing: no EGL display, no
  // OpenGL 4.3 core context (compute shaders).
  explicit GlComputeContext(const std::string& resource_root);
  ~GlComputeContext();
  GlComputeContext(const GlComputeContext&) = delete;
  GlComputeContext& operator=(const GlComputeContext&) = delete;

  EglContext& egl() { return egl_; }
  // The bond-force program (shaders/pd_bond_forces.comp) of that precision, compiled on the first
  // call with the context current. Throws std::runtime_error when it does not compile (fp64: a
  // driver without fp64 in its GLSL) or the file is missing.
  unsigned bond_force_program(DevicePrecision precision);
  // "GL: 4.5 (Core Profile) Mesa ...; renderer: llvmpipe ..."
  const std::string& description() const { return egl_.description(); }

 private:
  EglContext egl_;
  std::string resource_root_;
  unsigned programs_[2] = {0, 0};  // by precision
};

}  // namespace periflex
