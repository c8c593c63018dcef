#include "study/refine_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "solve/simulation.h"

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

// The beam the quantities describe: length from the clamp to the free end, depth, material.
struct Beam {
  double length = 0.0, depth = 0.0, youngs = 0.0, density = 0.0;
};

Beam beam_of(const StudyDef& study, const FlexBodyDef& body) {
  const auto refuse = [&](const std::string& what) {
    throw InputError(study_location(study, "refine.flex_body"), "a refine study needs " + what);
  };
  if (body.shape.kind != ShapeDef::Kind::kBox || body.shape.angle != 0.0)
    refuse("an unrotated box-shaped flexible body lying along x");
  const double right = body.shape.center.x() + 0.5 * body.shape.width;
  double clamp_edge = -std::numeric_limits<double>::infinity();
  for (const RegionLoadDef& load : body.loads)
    if (load.kind == RegionLoadDef::Kind::kPrescribedDisplacement && load.region.kind == ShapeDef::Kind::kBox)
      clamp_edge = std::max(clamp_edge, load.region.center.x() + 0.5 * load.region.width);
  if (!std::isfinite(clamp_edge)) refuse("a box-shaped prescribed_displacement load clamping the left end");
  Beam beam;
  beam.length = right - clamp_edge;
  beam.depth = body.shape.height;
  beam.youngs = body.material.youngs_modulus;
  beam.density = body.material.density;
  if (beam.length <= 0.0) refuse("the clamp on the left end of the beam");
  return beam;
}

}  // namespace

double first_extreme_time(const std::vector<double>& times, const std::vector<double>& values, bool minimum) {
  const double sign = minimum ? -1.0 : 1.0;
  for (size_t k = 1; k + 1 < values.size(); ++k) {
    const double a = sign * values[k - 1], b = sign * values[k], c = sign * values[k + 1];
    if (b > a && b >= c) {
      // vertex of the parabola through the three samples (equal spacing assumed)
      const double h = times[k + 1] - times[k];
      const double curvature = a - 2.0 * b + c;
      const double shift = curvature != 0.0 ? 0.5 * (a - c) / curvature : 0.0;
      return times[k] + std::clamp(shift, -1.0, 1.0) * h;
    }
  }
  return -1.0;
}

StudyResult run_refine_study(const StudyDef& study, const StudyLog& log_fn, const StudyStop& stop) {
  const auto log = [&](const std::string& line) {
    if (log_fn) log_fn(line);
  };
  StudyResult result;
  result.study = study;
  const SceneDef base = study_scene(study);
  result.scene_name = base.name;
  if (base.flex_bodies.empty())
    throw InputError(study_location(study, "study.scene"), "a refine study needs a scene with a [[flex_body]]");

  // the flexible body, the probe, and what the answer should be
  int body_index = 0;
  if (!study.refine.flex_body.empty()) {
    body_index = -1;
    for (size_t k = 0; k < base.flex_bodies.size(); ++k)
      if (base.flex_bodies[k].name == study.refine.flex_body) body_index = static_cast<int>(k);
    if (body_index < 0)
      throw InputError(study_location(study, "refine.flex_body"), "no flexible body '" + study.refine.flex_body + "'");
  }
  const FlexBodyDef& body = base.flex_bodies[body_index];
  const Beam beam = beam_of(study, body);
  std::string probe = study.refine.probe;
  if (probe.empty()) {
    for (const ProbeDef& p : base.probes)
      if (p.body == body.name) { probe = p.name; break; }
  }
  if (probe.empty()) throw InputError(study_location(study, "refine.probe"), "the flexible body has no probe");

  const bool wave = study.refine.quantity == "wave_speed";
  const double c = std::sqrt(beam.youngs / beam.density);
  // Euler-Bernoulli first cantilever mode: (beta L)^2 / (2 pi L^2) sqrt(E I / (rho A)), I / A = h^2 / 12
  const double beta_l = 1.875104068711961;
  const double frequency = beta_l * beta_l / (2.0 * kPi * beam.length * beam.length) * beam.depth * c /
                           std::sqrt(12.0);
  const double expected = wave ? c : frequency;
  // fixed-free bar: the stop wave from the clamp reaches the free end at L / c and reverses the tip
  const double extreme_at = wave ? beam.length / c : 0.5 / frequency;
  result.quantity = study.refine.quantity;
  result.quantity_unit = wave ? "m/s" : "Hz";
  result.reference_description = wave ? "wave speed sqrt(E / rho) = " + format_g(c) + " m/s, L = " + format_g(beam.length) + " m"
                                      : "Euler-Bernoulli first bending frequency " + format_g(frequency) +
                                            " Hz, L = " + format_g(beam.length) + " m, h = " + format_g(beam.depth) + " m";
  log("reference: " + result.reference_description);

  std::vector<double> spacings = study.refine.grid_spacing, ratios = study.refine.horizon_ratio;
  if (spacings.empty()) spacings.push_back(body.grid_spacing);
  if (ratios.empty()) ratios.push_back(body.horizon_ratio);
  const std::string integrator = study.methods.empty() ? base.solver.integrator : study.methods[0].integrator;
  // a method's step, scaled with each grid, in no more steps than the scene allows
  if (!study.methods.empty() && !study.methods[0].dt.empty()) {
    SceneDef timed = base;
    timed.solver.end_time = 1.6 * extreme_at;
    for (double dx : spacings)
      check_step_count(timed, study.methods[0].dt[0] * dx / body.grid_spacing, study.methods[0].where);
  }

  for (double ratio : ratios) {
    for (double dx : spacings) {
      if (result.stopped) break;
      StudyRow row;
      row.integrator = integrator;
      row.correction = "-";
      row.grid_spacing = dx;
      row.horizon_ratio = ratio;
      row.expected = expected;
      SceneDef scene = base;
      FlexBodyDef& flex = scene.flex_bodies[body_index];
      flex.grid_spacing = dx;
      flex.horizon_ratio = ratio;
      scene.solver.integrator = integrator;
      scene.solver.auto_substep = false;
      try {
        // the step: the method's, scaled with the grid, or half the explicit critical step
        double dt = 0.0;
        if (!study.methods.empty() && !study.methods[0].dt.empty()) {
          dt = study.methods[0].dt[0] * dx / body.grid_spacing;
        } else {
          Simulation probe_sim(scene);
          dt = 0.5 * probe_sim.info().critical_time_step;
        }
        if (!(dt > 0.0))
          throw InputError(study.methods.empty() ? study_location(study, "method") : study.methods[0].where,
                           "no time step: give [[method]] dt");
        scene.solver.dt = dt;
        row.dt = dt;
        scene.solver.end_time = 1.6 * extreme_at;

        const auto start = Clock::now();
        Simulation sim(scene);
        sim.initialize();
        double wall = std::chrono::duration<double>(Clock::now() - start).count();
        row.particles = sim.info().particles;
        int column = -1;
        const auto columns = sim.probe_columns();
        for (size_t k = 0; k < columns.size(); ++k)
          if (columns[k] == "probe." + probe + (wave ? ".x" : ".y")) column = static_cast<int>(k);
        if (column < 0) throw InputError(study_location(study, "refine.probe"), "no probe '" + probe + "'");
        // about 400 samples up to the expected extreme, taken between timed stretches of stepping
        const long every = std::max(1L, std::lround(extreme_at / 400.0 / dt));
        std::vector<double> times, values;
        const auto record = [&] {
          times.push_back(sim.time());
          values.push_back(sim.sample().probe_values[column]);
        };
        record();
        while (sim.time() < scene.solver.end_time) {
          const auto t0 = Clock::now();
          for (long s = 0; s < every; ++s) {
            if (stop && stop()) throw StudyStopped("stopped at t = " + format_g(sim.time()) + " s");
            sim.step();
          }
          wall += std::chrono::duration<double>(Clock::now() - t0).count();
          record();
        }
        row.wall_time = wall;
        row.steps = sim.step_count();
        const double t_extreme = first_extreme_time(times, values, !wave);
        if (t_extreme <= 0.0) {
          row.status = "failed: no extreme of the probe signal";
        } else {
          row.measured = wave ? beam.length / t_extreme : 0.5 / t_extreme;
          row.error_max_rel = std::abs(row.measured - expected) / expected;
          row.error_max = std::abs(row.measured - expected);
        }
      } catch (const NumericalError& e) {
        row.status = "failed: " + e.diagnostic().quantity;
      } catch (const StudyStopped&) {
        result.stopped = true;
        log("dx=" + format_g(dx) + " m=" + format_g(ratio) + ": stopped, not measured");
        break;
      }
      log("dx=" + format_g(dx) + " m=" + format_g(ratio) + ": " +
          (row.ok() ? format_g(row.measured) + " " + result.quantity_unit + " (error " +
                          format_g(row.error_max_rel) + ") in " + format_g(row.wall_time) + " s, " +
                          std::to_string(row.particles) + " particles"
                    : row.status));
      result.rows.push_back(row);
    }
  }
  return result;
}

}  // namespace periflex
