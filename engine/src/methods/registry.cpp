// The method registry: one row per method (methods.hpp), with the function that runs it
// (method_input.hpp). A new method adds its file, its Method value and one row here.
#include "methods/registry.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "dtlab/engine/methods.hpp"
#include "location/location_policy.hpp"

namespace dtlab::engine {
namespace {

struct MethodEntry {
  MethodInfo info;
  MethodRun run;
};

// clang-format off
const std::array kMethods{
  //          method                     name                  summary
  //          parallel min_threads dag walk flips cavity post_check spins   run
  MethodEntry{{Method::Sequential,        "sequential",         "one thread, no locks: the baseline",
               false, 1, true, true, true, true, false, false},  &run_sequential},
  MethodEntry{{Method::Pessimistic,       "pessimistic",        "lock-free location, then each insertion inside one global critical section (paper Sect. 5)",
               true,  1, true, true, true, true, false, false},  &run_pessimistic},
  MethodEntry{{Method::OptimisticDetect,  "optimistic-detect",  "per-tetrahedron locks; a wait that closes a cycle gives its insertion up by the undo log (paper Sect. 5)",
               true,  1, true, true, true, true, false, true},  &run_optimistic_detect},
  MethodEntry{{Method::OptimisticPrevent, "optimistic-prevent", "per-tetrahedron locks; never wait for a higher priority while holding a lock (paper Sect. 5)",
               true,  1, true, true, true, true, false, true},  &run_optimistic_prevent},
  MethodEntry{{Method::Burglary,          "burglary",           "per-tetrahedron locks, no undo: a deadlock is broken by taking the victim's locks, then a sequential post-check (paper Sect. 5)",
               true,  1, true, true, true, true, true, true},   &run_burglary},
  MethodEntry{{Method::Batch,             "batch",              "T - 1 threads locate without locks, one thread inserts what they found (described in the paper, built here)",
               true,  2, true, true, true, true, false, false},  &run_batch},
  MethodEntry{{Method::Partitioned,       "partitioned",        "no locks: each pass cuts a Hilbert curve through the points into one part a thread; an insertion that reaches another part waits for a pass whose curve and cuts differ (Marot, Pellerin, Remacle 2019)",
               true,  1, false, true, true, true, false, false,
               "its passes insert in the curve's order, not the random order the DAG's expected cost rests on, and it reuses dead slots, which the DAG keeps"},
               &run_partitioned},
  MethodEntry{{Method::LockGrid,          "lock-grid",          "a lock a cell of a spatial grid: a thread holds the cells of the vertices of what it changes; the lower thread id waits, the higher gives its insertion up by an undo log (after CGAL's Spatial_lock_grid_3 idea)",
               true,  1, false, true, true, true, false, true,
               "its undo log keeps no DAG children, and it reuses dead slots, which the DAG keeps"},
               &run_lock_grid},
};
// clang-format on

const MethodEntry& entry(Method method) {
  const auto index = static_cast<std::size_t>(method);
  if (index >= kMethods.size() || kMethods[index].info.method != method) {
    throw std::logic_error("dtlab: a method without its registry row");
  }
  return kMethods[index];
}

}  // namespace

std::span<const MethodInfo> methods() {
  static const std::array<MethodInfo, kMethods.size()> infos = [] {
    std::array<MethodInfo, kMethods.size()> all{};
    for (std::size_t i = 0; i < kMethods.size(); ++i) all[i] = kMethods[i].info;
    return all;
  }();
  return infos;
}

const MethodInfo& method_info(Method method) {
  return entry(method).info;
}

std::optional<Method> method_named(std::string_view name) {
  for (const MethodEntry& e : kMethods) {
    if (name == e.info.name) return e.info.method;
  }
  return std::nullopt;
}

std::string method_names() {
  std::string names;
  for (const MethodEntry& e : kMethods) {
    if (!names.empty()) names += " | ";
    names += e.info.name;
  }
  return names;
}

std::optional<std::string> unsupported(const TriangulateOptions& options) {
  const MethodInfo& info = method_info(options.method);
  const std::string method = std::string("--method ") + info.name;
  if (options.location == Location::Dag && !info.dag) {
    return method + " needs --location walk" +
           (info.walk_only_because != nullptr ? std::string(": ") + info.walk_only_because : "");
  }
  if (options.location == Location::Walk && !info.walk) return method + " needs --location dag";
  if (options.insertion == Insertion::Flips && !info.flips) {
    return method + " needs --insertion cavity";
  }
  if (options.insertion == Insertion::Cavity && !info.cavity) {
    return method + " needs --insertion flips";
  }
  if ((options.repair == Repair::Flips || options.repair == Repair::Rebuild) && !info.post_check) {
    return "--repair=flips and --repair=rebuild are the burglary method's post-check (--method "
           "burglary); --repair (star splaying) works with every method";
  }
  if (info.spins) {
    const int cpus = cpus_available();
    const int most = kSpinningThreadsPerCpu * cpus;
    if (options.threads > most) {
      return method + " at " + std::to_string(options.threads) + " threads: at most " +
             std::to_string(most) + " here (" + std::to_string(kSpinningThreadsPerCpu) +
             " a CPU, " + std::to_string(cpus) + (cpus == 1 ? " CPU" : " CPUs") +
             " available): its threads spin while they wait for a lock holder, which then "
             "gets a CPU too late (runs past 45 s or stopped by the watchdog, where 64 threads "
             "on 2 CPUs took under 2 s; docs/design.md, \"Threads a CPU\")";
    }
  }
  if (options.insertion == Insertion::Cavity && resolve_location(options.location).history) {
    // A cavity's tetrahedra have more successors than the history DAG's four children.
    return "--insertion cavity needs --location walk (the DAG mode's history keeps at most four "
           "children a tetrahedron)";
  }
  return std::nullopt;
}

MethodRun method_run(Method method) {
  return entry(method).run;
}

}  // namespace dtlab::engine
