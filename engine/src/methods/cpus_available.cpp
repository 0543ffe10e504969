// cpus_available() (dtlab/engine/methods.hpp).
#include <algorithm>
#include <thread>

#include "dtlab/engine/methods.hpp"

#if defined(__linux__)
#include <sched.h>
#endif

namespace dtlab::engine {

int cpus_available() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
#endif
  return static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
}

}  // namespace dtlab::engine
