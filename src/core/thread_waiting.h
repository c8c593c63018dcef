// How the OpenMP threads wait for each other. libgomp's default lets a thread that reaches a
// barrier spin for a long while (300,000 turns) before it sleeps; with another process busy on
// one of the cores the spinning thread takes that core from the thread everybody waits for, and
// two threads ran six times slower than one. Sleeping at once (passive waiting) keeps a shared
// machine fair but pays a wake-up at the end of every parallel loop, which cost the quiet
// two-thread speed-up. A brief spin (kSpinTurns, a few microseconds) catches the partner that
// is about to arrive on a quiet machine and still sleeps long before a descheduled one returns
// (figures in docs/running.md).
//
// libgomp reads its settings once, when it is loaded, before main runs, and the C library resets
// the environment after any earlier hook could change it. So the program sets GOMP_SPINCOUNT and
// starts itself again, once, at the top of main. A user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT
// is kept as it is (and then nothing is restarted).
#pragma once

namespace periflex {

// Turns a waiting thread spins before it sleeps (GOMP_SPINCOUNT).
inline constexpr const char* kSpinTurns = "300";

// At the top of main, before any OpenMP call: when neither variable is set, sets
// GOMP_SPINCOUNT=kSpinTurns and replaces the process by the same program with the same
// arguments. Returns only when nothing needed restarting, or when the restart failed (then the
// run goes on with libgomp's default).
void restart_with_brief_spinning(char** argv);

}  // namespace periflex
