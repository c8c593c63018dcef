#include "core/thread_waiting.h"

#include <unistd.h>

#include <cstdlib>

namespace periflex {

bool waiting_policy_is_set() {
  return std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr;
}

void restart_with_passive_waiting(char** argv) {
  if (waiting_policy_is_set()) return;
  setenv("OMP_WAIT_POLICY", "passive", 0);
  // the same executable, whatever PATH or the current folder say
  ::execv("/proc/self/exe", argv);
}

}  // namespace periflex
