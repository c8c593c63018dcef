#include "core/thread_waiting.h"

#include <unistd.h>

#include <cstdlib>

namespace periflex {

void restart_with_passive_waiting(char** argv) {
  // a user's own choice stands, and after the restart the variable is set: no second restart
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  setenv("OMP_WAIT_POLICY", "passive", 0);
  // the same executable, whatever PATH or the current folder say
  ::execv("/proc/self/exe", argv);
}

}  // namespace periflex
