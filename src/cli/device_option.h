// --device and solver.device: where the flexible bodies' bond forces run ("cpu", the default, or
// "gpu": OpenGL compute in solver.precision, docs/gpu.md). Checked before the model is built: a scene whose laws the GPU cannot run,
// or a machine without an OpenGL 4.3 compute context with fp64, is refused naming what is missing.
#pragma once

#include <string>

#include "scene/scene_def.h"

namespace periflex {

// Installs the GPU backend's factory for the solver (pd/bond_force_device.h) when the program
// was built with it, for as long as it lives: the program holds one over its run, so that the
// compute context the factory made is gone before the program's static objects are.
class GpuBackendInstallation {
 public:
  GpuBackendInstallation();
  ~GpuBackendInstallation();
  GpuBackendInstallation(const GpuBackendInstallation&) = delete;
  GpuBackendInstallation& operator=(const GpuBackendInstallation&) = delete;
};

// Sets scene.solver.device from the flag (empty: as the scene says); throws InputError naming
// --device or solver.device when "gpu" cannot run this scene here. Returns the device's description ("OpenGL compute fp64; GL: ...;
// renderer: ..."), empty for the CPU.
std::string apply_device_option(const std::string& device, SceneDef& scene);

// For `periflex check`: where the scene's forces run and whether the GPU path could run it here,
// and if not, why ("cpu (solver.device); the GPU path (fp64): available, OpenGL ...", or "...: not
// here: no OpenGL 4.3 context ..."). Makes a compute context to find out.
std::string device_report(const SceneDef& scene);

}  // namespace periflex
