#include "core/cpu_time.h"

#include <omp.h>

#include <ctime>

namespace periflex {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double omp_worker_cpu_seconds() {
  double total = 0.0;
#pragma omp parallel reduction(+ : total)
  {
    if (omp_get_thread_num() > 0) total += thread_cpu_seconds();
  }
  return total;
}

}  // namespace periflex
