#include "cli/device_option.h"

#include "cli/scene_setup.h"
#include "core/error.h"
#include "core/resources.h"
#include "pd/bond_force_device.h"
#ifdef PERIFLEX_WITH_GPU
#include "gpu/gl_bond_force_device.h"
#endif

namespace periflex {

GpuBackendInstallation::GpuBackendInstallation() {
#ifdef PERIFLEX_WITH_GPU
  install_bond_force_device(gl_bond_force_device_factory(find_resource_root()));
#endif
}

GpuBackendInstallation::~GpuBackendInstallation() { install_bond_force_device({}); }

std::string apply_device_option(const std::string& device, SceneDef& scene) {
  if (!device.empty()) scene.solver.device = device;
  if (scene.solver.device != "gpu") return "";
  // an error names what chose the GPU: the flag, or the scene's key
  const SourceLocation where = !device.empty() ? flag_location("--device") : scene.locate("solver.device");
  const std::string leave_out = !device.empty() ? "leave out --device gpu" : "set solver.device = \"cpu\"";
  // the laws first: they need no context to be refused
  for (const FlexBodyDef& def : scene.flex_bodies) {
    if (def.material.model == PdMaterialDef::Model::kBondBased) continue;
    throw InputError(where, "flexible body '" + def.name +
                                "' has a law that runs only on the CPU; only material.model = \"bond_based\" runs on the "
                                "GPU (" + leave_out + ")");
  }
  // then the context and the precision's program: made here, before the model, and kept for the
  // bodies' devices
  try {
    return make_bond_force_device(device_precision(scene.solver.precision))->description();
  } catch (const std::exception& e) {
    throw InputError(where, std::string("no GPU compute here: ") + e.what() + " (" + leave_out + " to run on the CPU)");
  }
}

std::string device_report(const SceneDef& scene) {
  const std::string precision = scene.solver.precision;
  std::string report = scene.solver.device + " (solver.device); the GPU path (" + precision + "): ";
  for (const FlexBodyDef& def : scene.flex_bodies)
    if (def.material.model != PdMaterialDef::Model::kBondBased)
      return report + "not for this scene: flexible body '" + def.name + "' has a law that runs only on the CPU";
  try {
    return report + "available, " + make_bond_force_device(device_precision(precision))->description();
  } catch (const std::exception& e) {
    return report + "not here: " + e.what();
  }
}

}  // namespace periflex
