#include "core/thread_waiting.h"

#include <unistd.h>

#include <cstdlib>

namespace periflex {

void restart_with_brief_spinning(char** argv) {
  // a user's own choice stands, and after the restart the variable is set: no second restart
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  setenv("GOMP_SPINCOUNT", kSpinTurns, 0);
  // the same executable, whatever PATH or the current folder say
  ::execv("/proc/self/exe", argv);
}

}  // namespace periflex
