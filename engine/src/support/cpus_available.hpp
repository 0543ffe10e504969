#pragma once
// The CPUs this process may run on: its affinity mask's (a container or taskset may allow fewer
// than the machine has), or the machine's logical CPUs where there is no mask to read.
namespace dtlab::engine {

int cpus_available();

}  // namespace dtlab::engine
