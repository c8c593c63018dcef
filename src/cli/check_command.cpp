#include "cli/check_command.h"

#include <cstdio>

#include "cli/device_option.h"
#include "cli/scene_setup.h"
#include "core/error.h"
#include "scene/grid_scan.h"
#include "solve/simulation.h"

namespace periflex {

namespace {

void print_list(const char* label, const std::vector<std::string>& items) {
  std::printf("  %-22s", label);
  if (items.empty()) std::printf("none");
  for (size_t k = 0; k < items.size(); ++k) std::printf("%s%s", k ? ", " : "", items[k].c_str());
  std::printf("\n");
}

}  // namespace

int check_command(const std::string& scene_path, const std::vector<std::string>& overrides) {
  const SceneDef scene = load_scene_with_options(scene_path, overrides);
  Simulation sim(scene);

  // Initial conditions are made consistent here, which also finds redundant constraints.
  // A step above the critical one is bad input found here: the report is still printed (it
  // names the critical step), then the error.
  std::string init_failure, input_failure;
  try {
    sim.initialize();
  } catch (const NumericalError& error) {
    init_failure = error.what();
  } catch (const InputError& error) {
    input_failure = error.what();
  }

  const ModelInfo& m = sim.info();
  const SolverDef& s = scene.solver;
  std::printf("scene %s (%s)\n", scene.name.c_str(), scene.path.c_str());
  if (!scene.description.empty()) std::printf("  %s\n", scene.description.c_str());
  std::printf("  %-22s%d (%d virtual)\n", "rigid bodies", m.bodies, m.virtual_bodies);
  std::printf("  %-22s%d\n", "joints", m.joints);
  std::printf("  %-22s%d\n", "drivers", m.drivers);
  std::printf("  %-22s%d\n", "force elements", m.force_elements);
  std::printf("  %-22s%d\n", "probes", m.probes);
  std::printf("  %-22s%d (%ld particles, %ld bonds)\n", "flexible bodies", m.flex_bodies, m.particles, m.bonds);
  // the peridynamic model of each flexible body, as the material selected it
  for (const FlexBodyDef& flex : scene.flex_bodies) {
    const PdMaterialDef& mat = flex.material;
    const char* plane = mat.plane_strain ? "plane strain" : "plane stress";
    if (mat.model == PdMaterialDef::Model::kStateBased)
      std::printf("  %-22s'%s': state-based (LPS), %s, poisson_ratio = %g\n", "peridynamic model", flex.name.c_str(),
                  plane, mat.poisson_ratio);
    else
      std::printf("  %-22s'%s': %s, %s, poisson_ratio = %s\n", "peridynamic model", flex.name.c_str(),
                  mat.model == PdMaterialDef::Model::kBilinearSoftening ? "bond-based, bilinear softening" : "bond-based",
                  plane, mat.plane_strain ? "1/4" : "1/3");
    // the blocks of its point file that carry materials of their own
    for (const BlockMaterialDef& block : flex.block_materials)
      std::printf("  %-22s'%s': block %ld, youngs_modulus = %g Pa, density = %g kg/m^3\n", "block material",
                  flex.name.c_str(), block.block, block.youngs_modulus, block.density);
    // where the body's geometry came from, and the box its particles fill
    Vec2 lo, hi;
    shape_bounds(flex.shape, lo, hi);
    std::printf("  %-22s'%s': %s, x in [%g, %g] m, y in [%g, %g] m\n", "geometry", flex.name.c_str(),
                flex.geometry_source.empty() ? "shape of the scene" : flex.geometry_source.c_str(), lo.x(), hi.x(),
                lo.y(), hi.y());
  }
  std::printf("  %-22s%d\n", "coordinates", m.coordinates);
  std::printf("  %-22s%d (%d redundant)\n", "constraint equations", m.constraint_equations, m.redundant_equations);
  print_list("redundant", m.redundant_constraints);
  std::printf("  %-22s%d\n", "degrees of freedom", m.degrees_of_freedom);
  print_list("active modules", m.active_modules);
  std::printf("  %-22s%s, dt = %g s, end time = %g s\n", "integrator", s.integrator.c_str(), s.dt, s.end_time);
  if (m.critical_time_step > 0) {
    std::printf("  %-22s%g s (dt / dt_crit = %.3g)\n", "critical time step", m.critical_time_step,
                s.dt / m.critical_time_step);
  }
  // what the budget expects the flexible bodies to need (compare with the limits it is held to)
  if (m.flex_bodies > 0) {
    const SceneBudget budget = check_scene_budget(scene);
    std::printf("  %-22s%.3g MB (limit %.3g MB)\n", "memory estimate", budget.memory / 1e6,
                memory_cap(scene.limits) / 1e6);
  }
  if (m.flex_bodies > 0) std::printf("  %-22s%s\n", "device", device_report(scene).c_str());
  std::printf("  %-22s%.3g (positions), %.3g (velocities)\n", "initial correction", m.initial_position_correction,
              m.initial_velocity_correction);
  for (const auto& w : m.warnings) std::printf("warning: %s\n", w.c_str());
  if (!input_failure.empty()) {
    std::fprintf(stderr, "periflex: error: %s\n", input_failure.c_str());
    return kExitBadInput;
  }
  if (!init_failure.empty()) {
    std::fprintf(stderr, "periflex: numerical failure at set-up: %s\n", init_failure.c_str());
    return kExitNumerical;
  }
  return kExitOk;
}

}  // namespace periflex
