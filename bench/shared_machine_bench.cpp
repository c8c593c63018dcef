// The solver on a machine it shares: the first 200 steps of scenes/glass_branching.toml (36k
// particles, the configuration the scene ships) on one and on two threads, on a quiet machine
// and with one other process keeping a core busy, as a desktop always has.
//
//   shared_machine_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// The threads are the solver's own team (core/thread_pool.h): a brief spin, then sleep, and the
// caller waits for the work, not for a worker kept off its core.
// Goals: with the busy process, two threads within 1.3x of one thread's wall time; quiet, two
// threads at least 1.6x faster than one.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <memory>
#include <optional>
#include <string>

#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

constexpr int kSteps = 200;

// A child process that spins on one core until it is killed.
class BusyProcess {
 public:
  BusyProcess() {
    pid_ = ::fork();
    if (pid_ == 0) {
      volatile unsigned long n = 0;
      for (;;) n = n + 1;
    }
  }
  ~BusyProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  BusyProcess(const BusyProcess&) = delete;
  BusyProcess& operator=(const BusyProcess&) = delete;

 private:
  pid_t pid_ = -1;
};

void GlassBranchingSteps(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const bool busy = state.range(1) != 0;
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/glass_branching.toml",
                                    {"solver.threads=" + std::to_string(threads)});
  omp_set_num_threads(threads);
  // the competitor spins for the whole measurement, set-up included
  std::optional<BusyProcess> competitor;
  if (busy) competitor.emplace();
  long bonds = 0;
  for (auto _ : state) {
    // the first steps of a fresh run each time: building the model is not timed
    state.PauseTiming();
    auto sim = std::make_unique<Simulation>(scene);
    sim->initialize();
    bonds = sim->info().bonds;
    state.ResumeTiming();
    for (int k = 0; k < kSteps; ++k) sim->step();
    state.PauseTiming();
    sim.reset();
    state.ResumeTiming();
  }
  state.counters["steps/s"] = benchmark::Counter(kSteps, benchmark::Counter::kIsIterationInvariantRate);
  // both stored directions of every bond, once per step: the whole step's rate, not the kernel's
  state.counters["bond evaluations/s"] =
      benchmark::Counter(2.0 * static_cast<double>(bonds) * kSteps, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(std::to_string(threads) + (threads == 1 ? " thread" : " threads") +
                 (busy ? ", one core busy" : ", quiet"));
}
BENCHMARK(GlassBranchingSteps)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->ArgNames({"threads", "busy"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace periflex

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
