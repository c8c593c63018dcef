// How the OpenMP threads wait for each other. libgomp's default lets a thread that reaches a
// barrier spin for a long while before it sleeps; with another process busy on one of the cores
// the spinning thread takes that core from the thread everybody waits for, and two threads ran
// six times slower than one. Passive waiting (sleep at once) costs a few microseconds per
// parallel loop on a quiet machine and keeps a shared one fair (figures in docs/performance.md).
//
// libgomp reads its settings when it is loaded, before main, so they are set from the program's
// pre-initialisation array, which the dynamic loader runs before any library's constructors.
// A user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT wins.
#include <cstdlib>

namespace {

void choose_passive_waiting(int, char**, char**) {
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr) {
    setenv("OMP_WAIT_POLICY", "passive", 0);
  }
}

}  // namespace

// placed in .preinit_array of the executable (this file is linked into the program itself)
__attribute__((section(".preinit_array"), used)) void (*const periflex_preinit_waiting)(int, char**, char**) =
    choose_passive_waiting;
