#pragma once
// The methods a run can use, each registered once (engine/src/methods/registry.cpp) with its
// name, a one-line summary and what it supports. The CLI's --method choices and help, the
// experiments' method lists and the checks of a run's options read this table, so a new method
// is a new file, its Method value and its row (docs/design.md, "What a change touches").
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "dtlab/engine/options.hpp"

namespace dtlab::engine {

struct MethodInfo {
  Method method;
  const char* name;     // as the CLI, the stats and the experiments write it
  const char* summary;  // one line, for --help and the docs
  bool parallel;        // runs on options.threads threads (false: one thread, no locks)
  int min_threads;      // threads it runs whatever options.threads says (batch: a locating and an
                        // inserting thread)
  bool dag;             // supports --location dag
  bool walk;            // supports --location walk
  bool flips;           // supports --insertion flips
  bool cavity;          // supports --insertion cavity
  bool post_check;      // has the paper's post-check: --repair=flips and --repair=rebuild
  bool spins;           // a thread that finds a lock taken spins and yields until its holder lets
                        // go: at most kSpinningThreadsPerCpu threads a CPU (unsupported())
  const char* walk_only_because = nullptr;  // why a method without dag needs the walk mode
};

// Every method, in the order of the Method enumeration.
std::span<const MethodInfo> methods();
const MethodInfo& method_info(Method method);
std::optional<Method> method_named(std::string_view name);
// "sequential | pessimistic | ...": every method's name, for help texts.
std::string method_names();

// The CPUs this process may run on: its affinity mask's (taskset and a container's cpuset narrow
// it; a CPU-time quota is not seen), or the machine's logical CPUs where there is no mask to read.
int cpus_available();

// The most threads a CPU available to the process that a method whose waits spin
// (MethodInfo::spins) is given. Its waiters take the CPUs from the holders they wait for, which
// get a turn only after the waiters: on 2 CPUs all four finished uniform:20000 and
// uniform:200000 in under 2 s at 64 threads, while at 256 optimistic-detect ran past 45 s and
// lock-grid took 27 s, and at 1,024 all four ran past 45 s on uniform:200000 (docs/design.md,
// "Threads a CPU"). Measured on 2 CPUs only.
inline constexpr int kSpinningThreadsPerCpu = 32;

// Why the engine cannot run `options` (a message for the user), or nothing: a location or
// insertion the method does not support, a post-check repair for a method without one, cavity
// insertion where the location mode keeps a history DAG, more threads than a method that spins
// runs on the CPUs available. triangulate() throws std::invalid_argument with it.
std::optional<std::string> unsupported(const TriangulateOptions& options);

}  // namespace dtlab::engine
