// Cost of particle contact in the steps of a body that tears: the shipped projectile through a
// glass plate (scenes/projectile_plate.toml), refined, against the same scene without its
// particle contact.
//
//   contact_tearing_bench --benchmark_counters_tabular=true
//
// The scene is read from its file by the scene loader, as `periflex run` reads it, with the grid
// spacing as the benchmark's argument (in um; the step scaled with it from the file's 40 ns at
// 0.5 mm) and one thread. The twin has its `particles` contact ("fragments") removed and keeps
// the slug's `rigid_particles` contact, so both are punched and shattered alike. Both are
// stepped in turn from the start through the slug's passage (the first 40 us: it strikes at
// 1.3 us and is through the 4 mm pane by about 30 us), each step timed on its own in the CPU
// time of its one thread, so that a busy machine weighs on both alike. Fragments fly at up to
// 150 m/s: the Verlet list of the contact is searched again whenever some particle has moved
// half its skin, every few tens of steps here, and those searches are part of the figure.
//
// Counters: the median step with and without contact and the share from the medians (1 -
// without / with); the share of the whole passage from the summed times; the most pairs in
// contact seen (sampled every 50 steps, outside the timing); the bonds broken at the end.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <ctime>
#include <string>
#include <vector>

#include "core/cpu_time.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

constexpr double kPassage = 40e-6;  // [s] stepped and timed

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double seconds_of_step(Simulation& sim) {
  const double start = thread_cpu_seconds();
  sim.step();
  return thread_cpu_seconds() - start;
}

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// arg: grid spacing in um
void BM_ContactShareOfTearingPlate(benchmark::State& state) {
  omp_set_num_threads(1);
  const double dx = 1e-6 * static_cast<double>(state.range(0));
  const std::vector<std::string> overrides{"flex_body.plate.grid_spacing=" + number(dx),
                                           "solver.dt=" + number(4e-8 * dx / 5e-4), "solver.threads=1"};
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/projectile_plate.toml", overrides);
  SceneDef bare = scene;
  std::erase_if(bare.contacts, [](const ContactDef& c) { return c.kind == ContactDef::Kind::kParticles; });
  for (auto _ : state) {
    Simulation with(scene), without(bare);
    with.initialize();
    without.initialize();
    std::vector<double> t_with, t_without;
    long pairs_max = 0;
    for (long n = 0; with.time() < kPassage; ++n) {
      t_without.push_back(seconds_of_step(without));
      t_with.push_back(seconds_of_step(with));
      if (n % 50 == 0) {
        state.PauseTiming();
        pairs_max = std::max(pairs_max, with.sample().contact_count);
        state.ResumeTiming();
      }
    }
    double sum_with = 0.0, sum_without = 0.0;
    for (double t : t_with) sum_with += t;
    for (double t : t_without) sum_without += t;
    const double m_with = median(t_with), m_without = median(t_without);
    state.counters["particles"] = static_cast<double>(with.info().particles);
    state.counters["steps"] = static_cast<double>(t_with.size());
    state.counters["with_ms"] = 1e3 * m_with;
    state.counters["without_ms"] = 1e3 * m_without;
    state.counters["contact%"] = m_with > 0.0 ? 100.0 * (1.0 - m_without / m_with) : 0.0;
    state.counters["contact%_sum"] = sum_with > 0.0 ? 100.0 * (1.0 - sum_without / sum_with) : 0.0;
    state.counters["pairs_max"] = static_cast<double>(pairs_max);
    state.counters["broken"] = static_cast<double>(with.sample().broken_bonds);
  }
}
// dx = 250 um (5120 particles) and 125 um (20480 particles); one passage each
BENCHMARK(BM_ContactShareOfTearingPlate)->Arg(250)->Arg(125)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
