// deadlocks (paper Fig. 14): deadlocks, stale wait cycles, give-ups and burglaries of the
// optimistic methods and burglary, against the thread count and the size.
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

using engine::Method;

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    for (const int threads : p.threads) {
      for (const Method method :
           {Method::OptimisticDetect, Method::OptimisticPrevent, Method::Burglary}) {
        RunSpec spec = base;
        spec.options.method = method;
        spec.options.threads = threads;
        spec.variant = engine::to_string(method);
        runs.push_back(spec);
      }
    }
  });
  return runs;
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "location", "threads", "method", "runs", "waits",
                       "deadlocks", "deadlocks per 1k points", "stale cycles", "give-ups",
                       "priority raises", "burglaries", "seconds"});
  for (const RowGroup& g : group_rows(t, {"input", "size_asked", "location", "threads", "method"},
                                      [&](const Row& r) { return is_ok(t, r); })) {
    const double points = aggregate_of(t, g.rows, "points").median;
    const auto median = [&](const char* column) {
      return fixed(aggregate_of(t, g.rows, column).median, 0);
    };
    const double deadlocks = aggregate_of(t, g.rows, "deadlocks").median;
    table.add({g.key[0], thousands(points), g.key[2], threads_cell(t, *g.rows.front()), g.key[4],
               std::to_string(g.rows.size()), median("waits"), fixed(deadlocks, 0),
               fixed(1000.0 * deadlocks / points, 2), median("stale_cycles"), median("give_ups"),
               median("priority_raises"), median("burglaries"),
               fixed(aggregate_of(t, g.rows, "seconds.total").median, 3)});
  }
  return table.str() +
         "\nMedians over the seeds. Detection and burglary count a deadlock only for a wait "
         "cycle that still holds (a cycle that dissolved before it was confirmed is a stale "
         "cycle); detection gives up on it, burglary breaks it by burgling. Prevention never "
         "waits for a thread of higher priority while it holds a lock: it raises its own "
         "priority and gives up instead, so it has no deadlocks.\n";
}

}  // namespace

Study deadlocks_study() {
  return {"deadlocks",
          "deadlocks, give-ups and burglaries against thread count and size (paper Fig. 14)",
          {5,
           2,
           {2, 4, 8},
           {2, 4},
           {10000, 50000, 100000, 200000},
           {3000},
           {"uniform"},
           {"uniform"},
           {engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
