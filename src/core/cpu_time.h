// Processor time, as opposed to wall time: what a run cost the machine. The solver's share is
// the time its own thread spent stepping plus what the team's worker threads have used
// (core/thread_pool.h: team_worker_cpu_seconds; the recording threads are left out, they have a
// figure of their own).
#pragma once

namespace periflex {

// Processor seconds used so far by the calling thread.
double thread_cpu_seconds();

}  // namespace periflex
