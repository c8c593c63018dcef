// Processor time, as opposed to wall time: what a run cost the machine. The solver's share is
// the time its own thread spent stepping plus what its OpenMP worker threads have used (the
// recording threads are left out: they have a figure of their own).
#pragma once

namespace periflex {

// Processor seconds used so far by the calling thread.
double thread_cpu_seconds();
// Processor seconds used so far by the OpenMP pool's worker threads (thread 0, the caller, left
// out). Runs one small parallel region to ask each worker.
double omp_worker_cpu_seconds();

}  // namespace periflex
