#include "cli/device_option.h"

#include <cmath>

#include "cli/scene_setup.h"
#include "core/error.h"
#include "core/resources.h"
#include "scene/cloud_lattice.h"
#include "scene/scene_budget.h"
#include "scene/toml_reader.h"
#include "pd/bond_force_device.h"
#ifdef PERIFLEX_WITH_GPU
#include "gpu/gl_bond_force_device.h"
#endif

namespace periflex {

namespace {

// The first flexible body only the CPU runs, with why ("has a law that runs only on the CPU");
// null when the GPU runs them all.
const FlexBodyDef* cpu_only_body(const SceneDef& scene, std::string& why) {
  for (const FlexBodyDef& def : scene.flex_bodies) {
    if (def.material.model != PdMaterialDef::Model::kBondBased) {
      why = "has a law that runs only on the CPU; only material.model = \"bond_based\" runs on the GPU";
      return &def;
    }
    // the GPU's bonds read their lengths from the grid's length classes
    const bool cloud_off_grid =
        def.particles && !cloud_nodes(*def.particles, def.grid_spacing, def.thickness, def.particles->source).on_grid;
    if (def.jitter > 0.0 || cloud_off_grid) {
      why = "has particles off the grid (jitter or a point file's layout), which only the CPU runs";
      return &def;
    }
    if (!def.block_materials.empty()) {
      why = "has materials by block (flex_body.block_material), which only the CPU runs";
      return &def;
    }
  }
  return nullptr;
}

// "1.49 MB", "3.2e+03 MB": memory as the message reads it
std::string megabytes(double bytes) { return format_number(std::round(bytes / 1e4) / 1e2) + " MB"; }

}  // namespace

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
  std::string why;
  if (const FlexBodyDef* def = cpu_only_body(scene, why))
    throw InputError(where, "flexible body '" + def->name + "' " + why + " (" + leave_out + ")");
  // then the context and the precision's program: made here, before the model, and kept for the
  // bodies' devices
  const DevicePrecision precision = device_precision(scene.solver.precision);
  std::unique_ptr<BondForceDevice> gpu;
  try {
    gpu = make_bond_force_device(precision);
  } catch (const std::exception& e) {
    throw InputError(where, std::string("no GPU compute here: ") + e.what() + " (" + leave_out + " to run on the CPU)");
  }
  // the bodies' bonds must fit the GPU's free memory (where its driver says how much that is)
  const SceneBudget budget = check_scene_budget(scene);
  const double needed = device_bytes_needed(budget.particles, 2.0 * budget.bonds, precision);
  const double free = gpu->free_memory();
  if (free >= 0.0 && needed > free)
    throw InputError(where, "the flexible bodies need about " + megabytes(needed) + " of GPU memory (" +
                                format_count(budget.particles) + " particles, " + scene.solver.precision +
                                ") and the GPU has " + megabytes(free) + " free; raise grid_spacing or lower "
                                "horizon_ratio, or " + leave_out + " to run on the CPU");
  return gpu->description();
}

std::string device_report(const SceneDef& scene) {
  const std::string precision = scene.solver.precision;
  std::string report = scene.solver.device + " (solver.device); the GPU path (" + precision + "): ";
  std::string why;
  if (const FlexBodyDef* def = cpu_only_body(scene, why))
    return report + "not for this scene: flexible body '" + def->name + "' " + why;
  try {
    return report + "available, " + make_bond_force_device(device_precision(precision))->description();
  } catch (const std::exception& e) {
    return report + "not here: " + e.what();
  }
}

}  // namespace periflex
