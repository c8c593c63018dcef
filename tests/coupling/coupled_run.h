// Small helpers shared by the coupled-scene tests: where the scenes are, running a simulation
// with a callback, reading probe columns.
#pragma once

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "scene/scene_def.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex::test {

// The scenes of these tests are small (at most 4000 particles): one thread is the fastest, and
// waiting OpenMP workers would only spin against the other test programs ctest runs alongside.
inline const bool kSingleThreaded = (omp_set_num_threads(1), true);

inline std::string scene_path(const std::string& stem) {
  return std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + stem + ".toml";
}

// Steps until `end` (simulated seconds), calling `visit` after initialize() and every `every` steps.
inline void run_until(Simulation& sim, double end, long every, const std::function<void(Simulation&)>& visit) {
  visit(sim);
  while (sim.time() < end - 1e-12) {
    sim.step();
    if (sim.step_count() % every == 0) visit(sim);
  }
  visit(sim);
}

// Column index of "probe.<name>.<component>" in Sample::probe_values; -1 when missing.
inline int probe_column(const Simulation& sim, const std::string& name, const std::string& component) {
  const std::vector<std::string> columns = sim.probe_columns();
  const std::string wanted = "probe." + name + "." + component;
  for (size_t k = 0; k < columns.size(); ++k) {
    if (columns[k] == wanted) return static_cast<int>(k);
  }
  return -1;
}

// A number in scientific notation for RecordProperty (std::to_string rounds small values to 0).
inline std::string sci(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6e", v);
  return text;
}

// Linear interpolation of the time at which a sampled signal crosses `level`.
inline double crossing_time(double t0, double v0, double t1, double v1, double level) {
  return t0 + (level - v0) * (t1 - t0) / (v1 - v0);
}

}  // namespace periflex::test
