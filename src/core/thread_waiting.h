// How the OpenMP threads wait for each other. libgomp's default lets a thread that reaches a
// barrier spin for a long while before it sleeps; with another process busy on one of the cores
// the spinning thread takes that core from the thread everybody waits for, and two threads ran
// six times slower than one. Passive waiting (sleep at once) costs little on a quiet machine and
// keeps a shared one fair (figures in docs/running.md).
//
// libgomp reads its settings once, when it is loaded, before main runs, and the C library resets
// the environment after any earlier hook could change it. So a program that wants passive
// waiting sets OMP_WAIT_POLICY and starts itself again, once, at the top of main. A user's own
// OMP_WAIT_POLICY or GOMP_SPINCOUNT is kept as it is (and then nothing is restarted).
#pragma once

namespace periflex {

// At the top of main, before any OpenMP call: when neither variable is set, sets
// OMP_WAIT_POLICY=passive and replaces the process by the same program with the same arguments.
// Returns only when nothing needed restarting, or when the restart failed (then the run goes on
// with libgomp's default).
void restart_with_passive_waiting(char** argv);

}  // namespace periflex
