// Cost of particle contact in a whole step at about 100k particles with a tenth of them in
// contact, against the same scene without the [[contact]] table.
//
//   contact_bench --benchmark_counters_tabular=true
//
// The scene (built as TOML text and read by the scene loader, as `periflex run` reads a file): a
// stack of six steel strips, 1000 x 17 particles each (102k in all), laid face on face with the
// faces 0.9 dx apart (the contact distance: touching, without force), squeezed by the prescribed
// velocity of the outer rows of the top and bottom strips. The compression waves close the five
// faces within about a microsecond and keep them closed while the rows go on pushing, so from the
// warm-up on the 2 x 5 x 1000 particles of the faces (9.8%) are in contact at every timed step.
// Fracture is on (its check is part of every step), one thread.
//
// The two scenes are stepped in turn inside one benchmark, each step timed on its own (CPU time
// of the one thread), so that a busy machine weighs on both alike. Counters: the median step
// with and without contact, the contact's share of the step (1 - without / with, from the
// medians), the fewest and most pairs in contact over the timed steps, and the particles in them
// as a share of all (two per pair: each face particle has one partner across). A second run with
// a skin of 1e-9 spacings searches the Verlet list again at every step: what a search costs.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

constexpr double kSpacing = 1e-4;  // dx [m]
constexpr int kColumns = 1000, kRows = 17, kStrips = 6;
constexpr double kSqueeze = 2.0;   // speed of the outer rows [m/s]

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// The stack as scene text; with_contact adds the particles contact over all strips, with a
// Verlet skin of skin_ratio spacings.
std::string stack_scene(bool with_contact, double skin_ratio = 0.5) {
  const double width = kColumns * kSpacing, height = kRows * kSpacing;
  // strip centre to strip centre: 16 spacings inside a strip, 0.9 across a face
  const double pitch = (kRows - 1 + 0.9) * kSpacing;
  std::ostringstream s;
  s << "[scene]\nname = \"contact_bench\"\ngravity = [0.0, 0.0]\n\n"
    << "[solver]\nintegrator = \"verlet\"\ndt = 1.0e-8\nend_time = 1.0\noutput_interval = 1.0e-6\nthreads = 1\n\n";
  for (int k = 0; k < kStrips; ++k) {
    const double y = k * pitch;
    s << "[[flex_body]]\nname = \"strip" << k << "\"\n"
      << "shape = { type = \"box\", center = [0.0, " << number(y) << "], width = " << number(width)
      << ", height = " << number(height) << " }\n"
      << "grid_spacing = " << number(kSpacing) << "\nthickness = 0.01\nhorizon_ratio = 3.0\nfracture = true\n\n"
      << "[flex_body.material]\nyoungs_modulus = 200.0e9\ndensity = 7850.0\nfracture_energy = 1.0e4\n\n";
    // the outer row of the bottom and the top strip pushes inwards
    if (k == 0 || k == kStrips - 1) {
      const double row = k == 0 ? y - 0.5 * (height - kSpacing) : y + 0.5 * (height - kSpacing);
      s << "[[flex_body.load]]\nname = \"squeeze\"\ntype = \"prescribed_velocity\"\n"
        << "region = { type = \"box\", center = [0.0, " << number(row) << "], width = " << number(2 * width)
        << ", height = " << number(0.5 * kSpacing) << " }\n"
        << "fy = " << number(k == 0 ? kSqueeze : -kSqueeze) << "\n\n";
    }
  }
  if (with_contact) {
    s << "[[contact]]\nname = \"stack\"\ntype = \"particles\"\nflex_bodies = [";
    for (int k = 0; k < kStrips; ++k) s << (k ? ", " : "") << "\"strip" << k << "\"";
    s << "]\nskin_ratio = " << number(skin_ratio) << "\n";
  }
  return s.str();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// CPU time of this thread: on one thread the step's own work, whatever else the machine runs
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds_of_step(Simulation& sim) {
  const double start = thread_seconds();
  sim.step();
  return thread_seconds() - start;
}

// A step of the stack with contact and one without, in turn; the benchmark's time is the pair.
void contact_share(benchmark::State& state, double skin_ratio) {
  omp_set_num_threads(1);
  Simulation with(parse_scene(stack_scene(true, skin_ratio), "contact_bench_with.toml"));
  Simulation without(parse_scene(stack_scene(false), "contact_bench_without.toml"));
  with.initialize();
  without.initialize();
  // the waves from both ends meet after about 1 us (100 steps): every face is closed by then
  const int warm_up = static_cast<int>(state.range(0));
  for (int k = 0; k < warm_up; ++k) {
    with.step();
    without.step();
  }
  std::vector<double> t_with, t_without;
  long pairs_min = -1, pairs_max = 0;
  for (auto _ : state) {
    t_without.push_back(seconds_of_step(without));
    t_with.push_back(seconds_of_step(with));
    // the pairs in contact, outside the timing (sample() evaluates the energies too)
    state.PauseTiming();
    const long pairs = with.sample().contact_count;
    pairs_min = pairs_min < 0 ? pairs : std::min(pairs_min, pairs);
    pairs_max = std::max(pairs_max, pairs);
    state.ResumeTiming();
  }
  const double m_with = median(t_with), m_without = median(t_without);
  const double particles = static_cast<double>(with.info().particles);
  state.counters["particles"] = particles;
  state.counters["with_ms"] = 1e3 * m_with;
  state.counters["without_ms"] = 1e3 * m_without;
  state.counters["contact%"] = m_with > 0.0 ? 100.0 * (1.0 - m_without / m_with) : 0.0;
  state.counters["pairs_min"] = static_cast<double>(pairs_min);
  state.counters["pairs_max"] = static_cast<double>(pairs_max);
  state.counters["in_contact%"] = 100.0 * 2.0 * static_cast<double>(pairs_min) / particles;
}

// The scene as a user would write it: the default skin of half a spacing; arg = warm-up steps.
void BM_ContactShareOfStep(benchmark::State& state) { contact_share(state, 0.5); }
BENCHMARK(BM_ContactShareOfStep)->Arg(200)->Iterations(60)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same with a skin of 1e-9 spacings: the Verlet list is searched again at every step, the
// cost a step pays whenever a bond has broken since the last (a tearing body).
void BM_ContactShareOfStepSearchingEveryStep(benchmark::State& state) { contact_share(state, 1e-9); }
BENCHMARK(BM_ContactShareOfStepSearchingEveryStep)->Arg(200)->Iterations(30)->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
