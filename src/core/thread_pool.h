// The solver's threads: loops of independent items run by the calling thread and a team of
// workers that take items as they become free. The team is the size OpenMP's setting gives the
// calling thread (OMP_NUM_THREADS, omp_set_num_threads, --threads), so that setting keeps working.
//
// Why not OpenMP's own parallel loops: a waiting libgomp thread spins for 300,000 turns before it
// sleeps, and with another process busy on a core that spinning took the core from the thread
// everybody waited for (two threads ran 2.3x slower than one). libgomp reads its waiting policy
// once, when it is loaded, so the program had to start itself again to change it; a library
// (the Python module) cannot. Here a worker spins briefly (kSpinTurns) and then sleeps, and the
// caller waits only for the items, never for a worker that has not started: an item is taken by
// whoever is running, so a worker that its core's other process keeps off holds nobody up.
#pragma once

#include <cstdint>
#include <type_traits>

namespace periflex {

// Turns a waiting thread spins (a pause instruction each, a few microseconds in all) before it
// sleeps: long enough to catch a partner about to arrive on a quiet machine, short enough to give
// the core back long before a descheduled partner returns.
inline constexpr int kSpinTurns = 300;

namespace detail {
// Runs call(context, item) for every item in [0, count) on the team (see parallel_for).
void run_on_team(int64_t count, void (*call)(void*, int64_t), void* context);
}  // namespace detail

// Calls fn(item) once for every item in [0, count), on the calling thread and its team. Items run
// in no set order and on any thread: fn must write disjoint data or results combined afterwards in
// item order. Runs on the calling thread alone when the team has one thread, when it is called
// from inside another parallel_for, or while another thread's loop holds the team. An exception
// thrown by fn stops further items from starting and is thrown again here.
template <typename Fn>
void parallel_for(int64_t count, Fn&& fn) {
  using Callable = std::remove_reference_t<Fn>;
  detail::run_on_team(
      count, [](void* context, int64_t item) { (*static_cast<Callable*>(context))(item); },
      const_cast<void*>(static_cast<const void*>(&fn)));
}

// Threads the calling thread's loops run on: the innermost TeamSizeScope's count on this thread,
// else OpenMP's setting for it (omp_get_max_threads).
int team_size();

// Sets the calling thread's team size for the scope's life and gives the previous one back at its
// end (threads <= 0: leaves it as it is). A Simulation holds one over each of its calls, so that
// its solver.threads applies to its own work and never to the thread that called it.
class TeamSizeScope {
 public:
  explicit TeamSizeScope(int threads);
  ~TeamSizeScope();
  TeamSizeScope(const TeamSizeScope&) = delete;
  TeamSizeScope& operator=(const TeamSizeScope&) = delete;

 private:
  int previous_;
};

// Processor time the team's workers have used since they started, in seconds (the calling
// thread's own time not included: thread_cpu_seconds() gives that).
double team_worker_cpu_seconds();

}  // namespace periflex
